// The sphere DEM path of `asperity run`: rigid spheres against spheres, planes and fixed boxes
// (dem/sphere_world.hpp), through the shared step policy, time loop and summary core.
#include "solver/run/run_spheres.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "solver/core/error.hpp"
#include "solver/core/format.hpp"
#include "solver/dem/cell_grid.hpp"
#include "solver/dem/sphere_world.hpp"
#include "solver/dem/time_step.hpp"
#include "solver/run/rebound.hpp"
#include "solver/run/summary.hpp"
#include "solver/run/time_loop.hpp"
#include "solver/run/vtk_series.hpp"
#include "solver/scene/resolve.hpp"

namespace asperity::run {
namespace {

// No body may start inside another: the first step would fire it out with a spurious force.
// The candidates come from the cell grid (dem/cell_grid.hpp, O(N): the test of every pair was
// 5·10⁹ distance tests at 100k spheres, 71 % of a 500-step run), fixed pairs included, with a
// skin of 10⁻⁶ of the smallest radius so that no pair the exact test below refuses is missed to
// round-off; the pairs come sorted by (i, j), so the first overlap named is the one the test of
// every pair named. The message names the key that allows it (a pressed packing).
void check_no_starting_overlap(const scene::SceneDef& s, const dem::SphereWorld& w) {
  const std::string where = s.file.string() + ": ";
  const int n = w.size();
  double r_min = std::numeric_limits<double>::infinity();
  for (const double r : w.radius) r_min = std::min(r_min, r);
  const std::vector<dem::PairContact> near = dem::neighbour_pairs(
      w.x, w.radius, std::vector<std::uint8_t>(static_cast<std::size_t>(n), 0), 1e-6 * r_min);
  auto pair = near.begin();
  for (int i = 0; i < n; ++i) {
    const auto& bi = s.bodies[w.body[i]];
    for (; pair != near.end() && pair->i == i; ++pair) {
      const int j = pair->j;
      const double gap = (w.x.col(i) - w.x.col(j)).norm() - w.radius[i] - w.radius[j];
      if (gap < 0) {
        throw InputError(where + "bodies[" + std::to_string(w.body[i]) + "] \"" + bi.name +
                         "\": position: starts overlapping \"" + s.bodies[w.body[j]].name +
                         "\" by " + fmt(-gap) + " m; allow_initial_overlap: true to start pressed");
      }
    }
    for (const dem::Wall& wall : w.walls) {
      double dist;
      if (wall.kind == dem::WallKind::plane) {
        dist = (w.x.col(i) - wall.a).dot(wall.b);
      } else {
        const Vec3 c = w.x.col(i).cwiseMax(wall.a).cwiseMin(wall.b);
        dist = (w.x.col(i) - c).norm();
        if (dist == 0) dist = -1;
      }
      if (dist < w.radius[i]) {
        throw InputError(where + "bodies[" + std::to_string(w.body[i]) + "] \"" + bi.name +
                         "\": position: starts inside \"" + s.bodies[wall.body].name +
                         "\" (overlap " + fmt(w.radius[i] - dist) +
                         " m; allow_initial_overlap: true to start pressed)");
      }
    }
  }
}

dem::SphereWorld build_sphere_world(const scene::SceneDef& s) {
  const std::string where = s.file.string() + ": ";
  dem::SphereWorld w;
  w.materials = s.materials;
  w.gravity = s.gravity;
  w.law.normal = scene::normal_law(s.contact.law);
  switch (s.contact.law) {
    case scene::ContactLaw::hertz:
      w.law.tangential = false;
      break;
    case scene::ContactLaw::hertz_mindlin:
      w.law.tangential = true;
      break;
    case scene::ContactLaw::linear:
      w.law.tangential = true;
      w.law.kn = *s.contact.kn;
      w.law.kt = scene::linear_kt(s.contact);
      break;
    case scene::ContactLaw::potential:
      throw InputError(where +
                       "contact.law: \"potential\" needs mesh bodies (model \"fem\" or a "
                       "rigid mesh); spheres use hertz, hertz-mindlin or linear");
    case scene::ContactLaw::volume_hertz:
    case scene::ContactLaw::volume_linear:
      throw InputError(where + "contact.law: \"" + scene::contact_law_name(s.contact.law) +
                       "\" needs rigid mesh bodies (a faceted sphere is shape \"mesh\"); "
                       "spheres use hertz, hertz-mindlin or linear");
  }
  w.law.friction = s.contact.friction;
  w.law.restitution = s.contact.restitution;

  std::vector<Vec3> x, v, om;
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    const scene::BodyDef& body = s.bodies[b];
    const std::string key = "bodies[" + std::to_string(b) + "] \"" + body.name + "\": ";
    if (const auto* sph = std::get_if<scene::SphereShape>(&body.shape)) {
      const double r = sph->radius;
      const double m = scene::sphere_mass(s, static_cast<int>(b));
      w.radius.push_back(r);
      w.mass.push_back(m);
      w.inertia.push_back(0.4 * m * r * r);
      w.material.push_back(body.material);
      w.body.push_back(static_cast<int>(b));
      w.fixed.push_back(body.fixed ? 1 : 0);
      x.push_back(body.position);
      v.push_back(body.fixed ? Vec3::Zero() : body.velocity);
      om.push_back(body.fixed ? Vec3::Zero() : body.angular_velocity);
    } else if (const auto* pl = std::get_if<scene::PlaneShape>(&body.shape)) {
      w.walls.push_back({.kind = dem::WallKind::plane,
                         .a = pl->point,
                         .b = pl->normal,
                         .material = body.material,
                         .body = static_cast<int>(b)});
    } else if (const auto* bx = std::get_if<scene::BoxShape>(&body.shape)) {
      w.walls.push_back({.kind = dem::WallKind::box,
                         .a = bx->min,
                         .b = bx->max,
                         .material = body.material,
                         .body = static_cast<int>(b)});
    } else {
      throw InputError(where + key +
                       "shape: mesh bodies are not available in this build's "
                       "solver (spheres, planes and boxes are)");
    }
  }
  const int n = static_cast<int>(x.size());
  w.x.resize(3, n);
  w.v.resize(3, n);
  w.w.resize(3, n);
  for (int i = 0; i < n; ++i) {
    w.x.col(i) = x[i];
    w.v.col(i) = v[i];
    w.w.col(i) = om[i];
  }

  // No body may start inside another: the first step would fire it out with a spurious force.
  // A scene that means it (a pressed packing) says so with allow_initial_overlap, and is not
  // checked: its starting overlaps are loads the contact law carries from the first step.
  if (!s.allow_initial_overlap) check_no_starting_overlap(s, w);
  dem::initialise(w);
  return w;
}

// The sphere world as the time loop sees it (run/time_loop.hpp).
struct SphereModel {
  dem::SphereWorld& w;
  int record = -1;
  int partner = -1;            // scene body, -1: the fixed targets
  std::vector<int> sphere_of;  // scene body → sphere index (-1: a wall)
  long every = 1;

  void prepare(bool) {}
  void step(double dt) { dem::step(w, dt); }
  std::string failure() const {
    if (w.max_overlap_ratio > 1) {
      return "runaway overlap (a body passed through another) at t = " + fmt(w.time) + " s";
    }
    return {};
  }
  const BodyContacts& contacts() const { return w.contacts; }
  Vec3 velocity(int body) const {
    const int i = sphere_of[static_cast<std::size_t>(body)];
    return i >= 0 ? Vec3(w.v.col(i)) : Vec3::Zero();
  }
  Vec3 relative_velocity() const {
    return partner >= 0 ? Vec3(velocity(record) - velocity(partner)) : velocity(record);
  }
  EnergyBalance energy() const { return dem::energy(w); }
  bool finite() const { return w.x.allFinite(); }
  double time() const { return w.time; }
  // Energy is checked every step for small scenes, else every row (it costs O(N)).
  long check_every() const { return w.size() <= 256 ? 1 : every; }
};

StepPrediction prediction_of(const dem::CriticalStep& crit) {
  const bool sized = crit.hertz_contact_time > 0;
  return {.critical = crit.critical,
          .limited_by = crit.limited_by,
          .shortest_contact =
              sized ? crit.hertz_contact_time : std::numeric_limits<double>::infinity()};
}

}  // namespace

StepChoice sphere_step(const scene::SceneDef& s, const RunOptions& options) {
  dem::SphereWorld w = build_sphere_world(s);
  return choose_step(s, options, prediction_of(dem::critical_step(w)), StepRegime::spheres);
}

RunResult run_spheres(const scene::SceneDef& s, const RunOptions& options) {
  dem::SphereWorld w = build_sphere_world(s);
  const dem::CriticalStep crit = dem::critical_step(w);
  const StepPrediction prediction = prediction_of(crit);
  const StepChoice step = choose_step(s, options, prediction, StepRegime::spheres);
  const RunIdentity id{.scene = s.name,
                       .model = "dem-spheres",
                       .contact_law = scene::contact_law_name(s.contact.law),
                       .recorded_body = s.bodies[s.record.body].name};
  if (!step.unresolved.empty()) return unresolved_run(id, step, prediction);

  SphereModel m{.w = w, .record = s.record.body, .every = std::max(1, s.record.every)};
  m.sphere_of.assign(s.bodies.size(), -1);
  std::vector<bool> free(s.bodies.size(), false);
  for (int i = 0; i < w.size(); ++i) {
    m.sphere_of[static_cast<std::size_t>(w.body[i])] = i;
    free[static_cast<std::size_t>(w.body[i])] = !w.fixed[i];
  }
  m.partner = restitution_partner(s.record.body, free);

  // ParaView frames: an observer of the loop.
  std::optional<SphereSeries> frames;
  if (options.vtk && options.vtk->every > 0) frames.emplace(w, *options.vtk);

  RunResult result;
  const LoopOutcome loop = run_model(m, frames, id, s, options, step, result);
  auto& j = result.summary;
  // Oblique-impact rebound of the recorded sphere (run/rebound.hpp; Chung & Ooi tests 4–8).
  if (const std::optional<FirstImpact> impact = first_impact(s)) {
    auto motion = [&](int body) {
      const int i = m.sphere_of[static_cast<std::size_t>(body)];
      return i >= 0 ? BodyMotion{.v = w.v.col(i), .w = w.w.col(i)} : BodyMotion{};
    };
    add_rebound_measures(s, *impact, motion(s.record.body), motion(impact->partner),
                         loop.restitution.ended(), j);
  }
  // The recorded sphere's final state (rebound and rolling checks); absent for a wall.
  if (const int i = m.sphere_of[static_cast<std::size_t>(s.record.body)]; i >= 0) {
    const Vec3 v = w.v.col(i), om = w.w.col(i);
    j["final_velocity"] = {v.x(), v.y(), v.z()};
    j["final_speed"] = v.norm();
    j["final_angular_velocity"] = {om.x(), om.y(), om.z()};
  }
  write_step(j, step, prediction);
  j["dt_rayleigh"] = crit.rayleigh;
  j["dt_contact"] = std::isfinite(crit.contact) ? SummaryJson(crit.contact) : SummaryJson();
  j["assumed_approach_speed"] = crit.approach_speed;
  write_run(j, w.steps, w.time, loop.ended_by_separation, loop.cpu_seconds, loop.wall_seconds);
  j["profile"] = profile_json(w.profile, loop.seconds_per_tick, false);
  j["neighbour_rebuilds"] = w.rebuilds;
  j["contact_updates"] = w.contact_updates;
  j["state_bytes"] = dem::state_bytes(w);
  j["damping"] = {{"form", s.contact.law == scene::ContactLaw::linear
                               ? "F = kn d + zeta sqrt(m* kn) d'"
                               : "F = K d^1.5 + zeta sqrt(m* K) d^0.25 d' (Tsuji form)"},
                  {"zeta_by_material_pair", [&] {
                     SummaryJson z = SummaryJson::object();
                     const int nm = static_cast<int>(w.materials.size());
                     for (int a = 0; a < nm; ++a)
                       for (int b = a; b < nm; ++b)
                         z[w.materials[a].name + "|" + w.materials[b].name] =
                             w.pair[a * nm + b].zeta;
                     return z;
                   }()}};
  return result;
}

}  // namespace asperity::run
