// `asperity particle --seed S --out FILE`: a reproducible rock-like particle surface; or
// `asperity particle --set SET.json --out DIR`: every particle a set lists (data/particles/).
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "app/cli_numbers.hpp"
#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "app/out_folder.hpp"
#include "solver/core/error.hpp"
#include "solver/geometry/random_particle.hpp"
#include "solver/geometry/repair_mesh.hpp"
#include "solver/geometry/write_mesh.hpp"
#include "solver/io/json_file.hpp"
#include "solver/io/plain_name.hpp"

namespace asperity::app {
namespace {
namespace fs = std::filesystem;

struct ParticleArgs {
  geometry::ParticleDef def;
  fs::path out, set;
  bool quiet = false;
};

void make_particle(const geometry::ParticleDef& def, const fs::path& out, bool quiet) {
  const SurfaceMesh mesh = geometry::random_particle(def);
  // The construction guarantees a valid solid (random_particle.hpp); checked all the same.
  const geometry::MeshCheck check = geometry::check_mesh(mesh, true);
  ASPERITY_CHECK(check.valid());
  if (!out.parent_path().empty()) fs::create_directories(out.parent_path());
  geometry::write_surface_mesh(out, mesh);
  if (!quiet) {
    std::cerr << "particle seed " << def.seed << ": " << mesh.faces.cols() << " triangles, volume "
              << check.volume << " m^3 -> " << out.string() << "\n";
  }
}

// data/particles/set.json: {"particles": [{"name", "seed", "size", ...}, ...]}; keys not given
// take ParticleDef's defaults. Every entry is read and checked before any particle is made: a bad
// entry is exit 2 with nothing written.
int make_set(const fs::path& set_file, const fs::path& dir, bool quiet) {
  const io::Json json = io::read_json_file(set_file);
  const io::JsonReader root(json, set_file, "");
  root.only_keys({"description", "format", "particles"});
  const std::string format = root.has("format") ? root.string("format") : "off";
  if (format != "off" && format != "obj" && format != "ply" && format != "stl")
    root.fail("format", "must be off, obj, ply or stl (got " + io::echo(format) + ")");
  const io::JsonReader list = root.child("particles");
  const std::size_t n = list.require_array();
  if (n == 0) list.fail("", "lists no particle");
  std::vector<std::pair<geometry::ParticleDef, fs::path>> todo;
  std::map<std::string, std::size_t> seen;  // name -> index, for duplicates
  for (std::size_t i = 0; i < n; ++i) {
    const io::JsonReader r = list.at(i);
    r.only_keys(
        {"name", "seed", "size", "elongation", "flatness", "angularity", "roughness", "faces"});
    const geometry::ParticleDef d = geometry::read_particle_def(r);
    if (const std::string problem = geometry::particle_def_problem(d); !problem.empty())
      r.fail("", problem);
    // The name is a file under --out: the rule every command applies to such names.
    const std::string name = r.string("name");
    if (const std::string problem = io::plain_name_problem(name); !problem.empty())
      r.fail("name", problem);
    if (const auto [it, fresh] = seen.emplace(name, i); !fresh)
      r.fail("name",
             io::echo(name) + " is also the name of particles[" + std::to_string(it->second) + "]");
    todo.emplace_back(d, dir / (name + "." + format));
  }
  for (const auto& [d, file] : todo) make_particle(d, file, quiet);
  return kExitOk;
}

}  // namespace

void add_particle_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<ParticleArgs>();
  auto* cmd = app.add_subcommand(
      "particle",
      "Generate a reproducible rock-like particle surface (closed, outward) into FILE "
      "(.off, .obj, .ply, .stl); or with --set, every particle a set file lists into DIR");
  cmd->add_option("--seed", args->def.seed, "Random seed (the same seed gives the same particle)")
      ->check(whole_number(0, std::numeric_limits<std::uint64_t>::max()));
  cmd->add_option("--out", args->out, "Output file (or folder with --set)")->required();
  cmd->add_option("--set", args->set, "A particle set (JSON, e.g. data/particles/set.json)");
  // A shape number parses as any finite value; particle_def_problem checks its range when the
  // command runs, with the message a set file's entry gets, and --help shows ParticleDef's default.
  const auto shape_number = [cmd](const std::string& flag, double& value, const std::string& help) {
    cmd->add_option(flag, value, help)->check(finite_number())->capture_default_str();
  };
  shape_number("--size", args->def.size, "Equivalent-sphere diameter, m");
  shape_number("--elongation", args->def.elongation, "b/a of the base ellipsoid, (0, 1]");
  shape_number("--flatness", args->def.flatness, "c/b of the base ellipsoid, (0, 1]");
  shape_number("--angularity", args->def.angularity, "Planar cuts: 0 none to 1 many and deep");
  shape_number("--roughness", args->def.roughness, "Multi-scale surface noise, 0 to 1");
  cmd->add_option("--faces", args->def.faces, "Triangle count (rounded to 20 n^2)")
      ->check(whole_number(0, 2'000'000))
      ->capture_default_str();
  add_quiet(*cmd, args->quiet, "No summary line on stderr");
  cmd->callback([args, cmd, &action] {
    if (!args->set.empty() && cmd->count("--seed") > 0)
      throw CLI::ValidationError("--set", "give --seed or --set, not both");
    if (args->set.empty() && cmd->count("--seed") == 0)
      throw CLI::RequiredError("--seed (or --set)");
    action = [args] {
      if (!args->set.empty()) {
        check_out_folder(args->out);
        return make_set(args->set, args->out, args->quiet);
      }
      check_out_file(args->out);
      if (const std::string problem = geometry::particle_def_problem(args->def); !problem.empty()) {
        throw InputError("particle: --" + problem);  // the problem starts with the key
      }
      make_particle(args->def, args->out, args->quiet);
      return kExitOk;
    };
  });
}

}  // namespace asperity::app
