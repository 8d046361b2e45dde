// `asperity mesh INPUT --faces N --out DIR [--element-size H]`: check and repair a surface mesh,
// simplify it to exactly N triangles, tetrahedralize it keeping them (bisected in their planes to
// H when given); DIR/surface.off, DIR/tets.vtk, DIR/mesh.json.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/cli_numbers.hpp"
#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "app/out_folder.hpp"
#include "solver/core/error.hpp"
#include "solver/core/format.hpp"
#include "solver/geometry/mesh_pipeline.hpp"

namespace asperity::app {
namespace {
namespace fs = std::filesystem;

// `asperity mesh`: its name and its help paragraph.
constexpr CommandText kMesh{
    .name = "mesh",
    .about =
        "Check a surface mesh (STL, OBJ, PLY, OFF), simplify it to exactly N triangles and "
        "tetrahedralize it keeping them: writes DIR/surface.off, DIR/tets.vtk, DIR/mesh.json",
};

struct MeshArgs {
  fs::path input, out;
  long faces = 0;
  double scale = 1.0;
  double quality = geometry::TetOptions{}.radius_edge_ratio;
  double min_dihedral = 0;
  double element_size = 0;
  const CLI::Option* element_size_option = nullptr;  // count() > 0: --element-size given
  double contact_patch = 0;
  bool no_tets = false, quiet = false;
};

int cmd_mesh(const MeshArgs& a) {
  geometry::PipelineOptions options;
  options.faces = a.faces;
  options.contact_patch = a.contact_patch;
  options.read.scale = a.scale;
  options.tetrahedralize = !a.no_tets;
  options.tet.radius_edge_ratio = a.quality;
  options.tet.min_dihedral_deg = a.min_dihedral;
  if (a.element_size_option->count() > 0) {
    if (!(a.element_size > 0)) {  // NaN too
      throw InputError(a.input.string() + ": --element-size: " + fmt(a.element_size) +
                       " is not a positive length in metres");
    }
    options.tet.element_size.size = a.element_size;
    options.element_size_key = a.input.string() + ": --element-size";
  }
  check_out_folder(a.out);
  if (!a.quiet && a.element_size_option->count() > 0) {
    // A fine element size meshes for minutes with nothing else to show (issue 31, class 11).
    const double budget = options.tet.time_budget_s;
    options.on_tetrahedralize = [&a, budget](double tets) {
      std::cerr << a.input.string() << ": tetrahedralizing, about " << std::round(tets / 1e3) / 1e3
                << " M tetrahedra estimated (TetGen stops at " << budget << " s)\n";
    };
  }
  const geometry::PreparedParticle p = geometry::prepare_particle(a.input, options);
  geometry::write_prepared_particle(p, a.out);
  if (!a.quiet) {
    for (const auto& w : p.log.warnings)
      std::cerr << "asperity: warning: " << a.input.string() << ": " << w << "\n";
    std::cerr << a.input.string() << ": " << p.source.faces.cols() << " -> "
              << p.surface.faces.cols() << " triangles, volume change "
              << p.change.volume_change_rel << ", max asperity " << p.change.max_asperity_rel_source
              << " -> " << p.change.max_asperity_rel;
    if (!a.no_tets) {
      std::cerr << ", " << p.quality.tets << " tets (edges " << p.quality.smallest_edge << " to "
                << p.quality.longest_edge << " m, min dihedral " << p.quality.min_dihedral_deg
                << " deg)";
    }
    std::cerr << " -> " << a.out.string() << "\n";
  }
  return kExitOk;
}

}  // namespace

void add_mesh_command(CLI::App& app, Action& action) {
  const auto [cmd, args] = add_command<MeshArgs>(app, action, kMesh, cmd_mesh);
  cmd->add_option("input", args->input, "Surface mesh file (.stl, .obj, .ply, .off)")->required();
  cmd->add_option("--faces", args->faces,
                  "Exact triangle count of the result: even, at least 4, at most the input's "
                  "(default: keep)")
      ->check(whole_number(0, 10'000'000));
  add_out_folder(*cmd, args->out);
  cmd->add_option("--scale", args->scale,
                  "Factor to metres for every coordinate (1e-3 for millimetres)")
      ->check(real_number(0, 1e6, true));
  cmd->add_option("--quality", args->quality,
                  "TetGen radius-edge bound with interior points only (0: no refinement)")
      ->check(real_number(0, 1e6, false));
  cmd->add_option("--min-dihedral", args->min_dihedral,
                  "TetGen smallest dihedral angle asked for, degrees")
      ->check(real_number(0, 70, false));
  args->element_size_option = cmd->add_option(
      "--element-size", args->element_size,
      "Target tetrahedron edge length, m (after --scale): the surface triangles are "
      "bisected in their own planes to it and the interior filled with quality "
      "tetrahedra (default: the surface triangles are the elements' faces)");
  cmd->add_option("--contact-patch", args->contact_patch,
                  "Radius, m (after --scale): keep every input triangle within it of the lowest "
                  "vertex and simplify only the rest, to the density of a --faces-triangle "
                  "particle (a contact-local surface, docs/geometry.md)")
      ->check(real_number(0, 1e6, false));
  cmd->add_flag("--no-tets", args->no_tets, "Surface only: no tetrahedralization");
  add_quiet(*cmd, args->quiet, "No summary line on stderr");
}

}  // namespace asperity::app
