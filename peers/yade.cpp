// The YADE adapter (Debian's YADE 2023.02a, `yade -n -x`): the scene as asperity resolved it goes
// to DIR/yade/input.json; scene_to_yade.py builds it in YADE, times a plain run, and records the
// force on the recorded body and the free spheres' motion every step (raw.csv, raw.json). The law
// mapping, the damping map β = ζ/√6 and the wall R* treatment are in docs/crosscheck.md.
//
// Rigid convex polyhedra under volume-linear take YADE's Polyhedra path (yade_polyhedra.py, input
// from yade_polyhedra_input.cpp): YADE's own overlap (depth V/A and normal) comes back with the
// trace, since asperity does not recompute a polyhedral intersection from YADE's positions, and
// raw.json adds the wall time of YADE's free-flight, contact, first and last contact steps.
#include <fstream>

#include "peers/peer_adapters.hpp"
#include "peers/yade_polyhedra_input.hpp"
#include "solver/core/error.hpp"
#include "solver/scene/resolve.hpp"

#ifndef ASPERITY_YADE_SCRIPT
#error "ASPERITY_YADE_SCRIPT (path of peers/scene_to_yade.py) must be defined by the build"
#endif

namespace asperity::peers {
namespace {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

Json vec(const Vec3& v) {
  return Json::array({v.x(), v.y(), v.z()});
}

// Rigid polyhedra: a scene with a mesh body, or under a volume law (YADE's Polyhedra path).
bool polyhedra(const scene::SceneDef& s) {
  if (s.contact.law == scene::ContactLaw::volume_linear ||
      s.contact.law == scene::ContactLaw::volume_hertz)
    return true;
  for (const scene::BodyDef& b : s.bodies)
    if (std::holds_alternative<scene::MeshShape>(b.shape)) return true;
  return false;
}

// Throws InputError for what YADE's mapping cannot express (the script checks the rest: a plane
// normal to no axis, a damped linear law).
void check(const scene::SceneDef& s) {
  const std::string where = s.file.string() + ": ";
  if (s.contact.law == scene::ContactLaw::potential) {
    throw InputError(where +
                     "contact.law: yade: \"potential\" has no YADE counterpart in the cross-check "
                     "(spheres, planes and boxes with hertz, hertz-mindlin or linear; rigid "
                     "convex polyhedra with volume-linear)");
  }
  if (polyhedra(s)) {
    // The polyhedra input checks the law, the models and each body's convexity.
    (void)yade_polyhedra_input(s, 0.0, 0);
    return;
  }
  for (std::size_t k = 0; k < s.bodies.size(); ++k) {
    const scene::BodyDef& b = s.bodies[k];
    const std::string at = where + "bodies[" + std::to_string(k) + "] \"" + b.name + "\": ";
    if (b.model != scene::Model::rigid)
      throw InputError(at + "model: yade: the cross-check runs rigid bodies only");
  }
}

// What scene_to_yade.py reads: the scene with everything asperity derives from it resolved.
Json yade_input(const scene::SceneDef& s, const Resolved& r) {
  Json j;
  j["scene"] = s.name;
  const bool linear = s.contact.law == scene::ContactLaw::linear;
  j["law"] = s.contact.law == scene::ContactLaw::hertz           ? "hertz"
             : s.contact.law == scene::ContactLaw::hertz_mindlin ? "hertz-mindlin"
                                                                 : "linear";
  if (linear) {
    j["kn"] = *s.contact.kn;
    j["kt"] = scene::linear_kt(s.contact);
  }
  // The hertz law has no tangential force: friction 0 caps YADE's shear force at zero.
  if (s.contact.law == scene::ContactLaw::hertz)
    j["friction_override"] = 0.0;
  else if (s.contact.friction)
    j["friction_override"] = *s.contact.friction;
  else
    j["friction_override"] = nullptr;
  j["materials"] = Json::object();
  for (const Material& m : s.materials) {
    j["materials"][m.name] = {{"density", m.density},
                              {"young", m.young},
                              {"poisson", m.poisson},
                              {"friction", m.friction},
                              {"restitution", m.restitution}};
  }
  j["pairs"] = Json::array();
  for (std::size_t a = 0; a < s.materials.size(); ++a) {
    for (std::size_t b = a; b < s.materials.size(); ++b) {
      j["pairs"].push_back(
          {{"a", s.materials[a].name},
           {"b", s.materials[b].name},
           {"zeta", scene::pair_constants(s.contact, s.materials[a], s.materials[b]).zeta}});
    }
  }
  j["bodies"] = Json::array();
  for (const scene::BodyDef& b : s.bodies) {
    Json body{{"name", b.name},
              {"material", s.materials[b.material].name},
              {"fixed", b.fixed},
              {"position", vec(b.position)},
              {"velocity", vec(b.fixed ? Vec3::Zero() : b.velocity)},
              {"angular_velocity", vec(b.fixed ? Vec3::Zero() : b.angular_velocity)}};
    if (const auto* sp = std::get_if<scene::SphereShape>(&b.shape)) {
      body["shape"] = {{"type", "sphere"}, {"radius", sp->radius}};
    } else if (const auto* pl = std::get_if<scene::PlaneShape>(&b.shape)) {
      body["shape"] = {{"type", "plane"}, {"point", vec(pl->point)}, {"normal", vec(pl->normal)}};
    } else if (const auto* bx = std::get_if<scene::BoxShape>(&b.shape)) {
      body["shape"] = {{"type", "box"}, {"min", vec(bx->min)}, {"max", vec(bx->max)}};
    }
    j["bodies"].push_back(body);
  }
  j["gravity"] = vec(s.gravity);
  j["dt"] = r.dt;
  j["steps"] = r.steps;
  j["record_body"] = s.bodies[s.record.body].name;
  return j;
}

PeerTrace run(const scene::SceneDef& s, const Resolved& r, const fs::path& exe, const fs::path& dir,
              RunMode mode) {
  const fs::path script = ASPERITY_YADE_SCRIPT;
  if (!fs::is_regular_file(script))
    throw PeerFailure("yade: " + script.string() + ": translator script not found");
  const bool poly = polyhedra(s);
  Json in = poly ? yade_polyhedra_input(s, r.dt, r.steps) : yade_input(s, r);
  in["cost_only"] = mode == RunMode::cost;  // scene_to_yade.py: the plain run alone
  write_file(dir / "input.json", in.dump(2) + "\n");
  run_translator("yade", shell_quote(exe.string()) + " -n -x " + shell_quote(script.string()), dir);
  const Json raw = Json::parse(std::ifstream(dir / "raw.json"));
  if (mode == RunMode::cost) {
    PeerTrace tr;
    tr.cpu_seconds = raw.at("cpu_seconds").get<double>();
    tr.wall_seconds = raw.at("wall_seconds").get<double>();
    tr.version = raw.value("yade_version", "");
    return tr;
  }
  const std::vector<int> traced = traced_bodies(s, poly);
  PeerTrace tr = read_trace_csv(dir / "raw.csv", static_cast<int>(traced.size()), "yade", poly);
  for (int b : traced) {
    const auto& w = raw.at("final").at(s.bodies[b].name).at("angular_velocity");
    tr.final_w.emplace_back(w[0].get<double>(), w[1].get<double>(), w[2].get<double>());
  }
  tr.cpu_seconds = raw.at("cpu_seconds").get<double>();
  tr.wall_seconds = raw.at("wall_seconds").get<double>();
  tr.version = raw.value("yade_version", "");
  tr.extra["stiffness"] = raw.at("stiffness");
  double worst = 0;
  for (const auto& k : raw.at("stiffness")) worst = std::max(worst, k.at("rel_diff").get<double>());
  tr.extra["stiffness_rel_diff_max"] = worst;
  // The polyhedra path times each kind of step: free flight, in contact, the first and last
  // contact steps (where YADE's intersection is known to be slowest).
  if (raw.contains("step_seconds")) tr.extra["step_seconds"] = raw.at("step_seconds");
  return tr;
}

}  // namespace

Adapter yade_adapter() {
  return {
      .name = "yade",
      .program = "yade",
      .package = "yade",
      .cpu_note = "YADE's engine loop alone (a second run, without the per-step Python recorder)",
      .check = check,
      .run = run};
}

}  // namespace asperity::peers
