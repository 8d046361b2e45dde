// Scene → world → time loop → measures. The sphere DEM path (rigid spheres, planes, boxes).
#include "run/run_scene.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <numbers>
#include <sstream>

#include "core/error.hpp"
#include "core/ticks.hpp"
#include "dem/sphere_world.hpp"
#include "dem/time_step.hpp"
#include "io/atomic_file.hpp"
#include "run/impact_measures.hpp"
#include "run/rebound.hpp"
#include "run/run_fdem.hpp"
#include "run/run_monitor.hpp"

namespace asperity::run {
namespace {

std::string fmt(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

const char* law_name(scene::ContactLaw law) {
  switch (law) {
    case scene::ContactLaw::hertz:
      return "hertz";
    case scene::ContactLaw::hertz_mindlin:
      return "hertz-mindlin";
    case scene::ContactLaw::linear:
      return "linear";
    case scene::ContactLaw::potential:
      return "potential";
    case scene::ContactLaw::volume_hertz:
      return "volume-hertz";
    case scene::ContactLaw::volume_linear:
      return "volume-linear";
  }
  return "?";
}

dem::SphereWorld build_sphere_world(const scene::SceneDef& s) {
  const std::string where = s.file.string() + ": ";
  dem::SphereWorld w;
  w.materials = s.materials;
  w.gravity = s.gravity;
  switch (s.contact.law) {
    case scene::ContactLaw::hertz:
      w.law.normal = contact::NormalLaw::hertz;
      w.law.tangential = false;
      break;
    case scene::ContactLaw::hertz_mindlin:
      w.law.normal = contact::NormalLaw::hertz;
      w.law.tangential = true;
      break;
    case scene::ContactLaw::linear:
      w.law.normal = contact::NormalLaw::linear;
      w.law.tangential = true;
      w.law.kn = *s.contact.kn;
      // Default k_t/k_n = 2/7: equal normal and tangential periods for a solid sphere
      // (Schäfer, Dippel & Wolf 1996).
      w.law.kt = s.contact.kt.value_or(2.0 / 7.0 * w.law.kn);
      break;
    case scene::ContactLaw::potential:
      throw InputError(where +
                       "contact.law: \"potential\" needs mesh bodies (model \"fem\" or a "
                       "rigid mesh); spheres use hertz, hertz-mindlin or linear");
    case scene::ContactLaw::volume_hertz:
    case scene::ContactLaw::volume_linear:
      throw InputError(where + "contact.law: \"" + law_name(s.contact.law) +
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
      const double m =
          s.materials[body.material].density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
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
  w.record_body = s.record.body;

  // No body may start inside another: the first step would fire it out with a spurious force.
  for (int i = 0; i < n; ++i) {
    const auto& bi = s.bodies[w.body[i]];
    for (int j = i + 1; j < n; ++j) {
      const double gap = (w.x.col(i) - w.x.col(j)).norm() - w.radius[i] - w.radius[j];
      if (gap < 0) {
        throw InputError(where + "bodies[" + std::to_string(w.body[i]) + "] \"" + bi.name +
                         "\": position: starts overlapping \"" + s.bodies[w.body[j]].name +
                         "\" by " + fmt(-gap) + " m");
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
                         "\" (overlap " + fmt(w.radius[i] - dist) + " m)");
      }
    }
  }
  dem::initialise(w);
  return w;
}

double cpu_seconds() {
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

// Sphere DEM default dt_safety: ≥ 200 steps per contact keep the energy error below 1e-4.
constexpr double kSphereSafety = 0.01;

}  // namespace

RunResult run_scene(const scene::SceneDef& s, const RunOptions& options) {
  if (is_fdem_scene(s)) return run_fdem(s, options);  // mesh bodies: the FEM/DEM path
  const std::string where = s.file.string() + ": ";
  dem::SphereWorld w = build_sphere_world(s);
  const dem::CriticalStep crit = dem::critical_step(w);

  const std::optional<double> given =
      options.dt_factor ? std::optional<double>(*options.dt_factor * crit.critical)
                        : (options.dt ? options.dt : s.dt);
  double dt = 0;
  if (options.dt_factor && !std::isfinite(crit.critical)) {
    throw InputError(where + "dt: no predicted critical step to scale (no free body)");
  }
  if (options.dt_factor) {
    dt = *given;
  } else if (given) {
    dt = *given;
    if (dt > crit.critical && !(options.allow_unsafe_dt || s.allow_unsafe_dt)) {
      throw InputError(where + "dt: " + fmt(dt) + " s exceeds the predicted critical step " +
                       fmt(crit.critical) + " s (limited by " + crit.limited_by +
                       "); use \"auto\", a smaller dt, or allow_unsafe_dt: true");
    }
  } else {
    if (!std::isfinite(crit.critical)) {
      throw InputError(where +
                       "dt: \"auto\" has no critical step to scale (no free sphere); give dt in s");
    }
    dt = s.dt_safety.value_or(kSphereSafety) * crit.critical;
  }
  const double n_steps_real = std::ceil(s.duration / dt - 1e-9);
  if (n_steps_real > 2e9) {
    throw InputError(where + "duration: " + fmt(s.duration) + " s needs " + fmt(n_steps_real) +
                     " steps of " + fmt(dt) + " s (over 2e9)");
  }
  const long n_steps = static_cast<long>(n_steps_real);

  RunResult result;
  const auto wall0 = std::chrono::steady_clock::now();
  const double cpu0 = cpu_seconds();
  const std::uint64_t ticks0 = ticks();
  ImpactMeasures im;
  im.start(0, w.record_force, w.record_overlap);
  auto balance = [](const dem::EnergyTerms& e) {
    return EnergyBalance{.kinetic = e.kinetic,
                         .contact = e.contact,
                         .gravity = e.gravity,
                         .dissipated = e.dissipated};
  };
  const dem::EnergyTerms e0 = dem::energy(w);
  RunMonitor monitor(s.name, balance(e0), s.unstable_energy_growth, n_steps, options.progress);
  auto push_rows = [&](const dem::EnergyTerms& e) {
    if (!options.keep_rows) return;
    const Vec3& f = w.record_force;
    result.force.push_back({w.time, f.x(), f.y(), f.z(), f.norm()});
    result.energy.push_back(
        {w.time, e.kinetic, 0.0, e.contact, e.gravity, e.dissipated, e.total()});
  };
  push_rows(e0);
  // Energy is checked every step for small scenes, else every `every` steps (it costs O(N)).
  const long check_every = w.size() <= 256 ? 1 : std::max(1, s.record.every);
  bool ended_by_separation = false;
  for (long k = 1; k <= n_steps && !monitor.unstable(); ++k) {
    dem::step(w, dt);
    im.add(w.time, w.record_force, w.record_overlap);
    ended_by_separation =
        s.record.end_after_separation && im.separated_for(w.time, *s.record.end_after_separation);
    const bool row = k % s.record.every == 0 || k == n_steps || ended_by_separation;
    if (row || k % check_every == 0) {
      const dem::EnergyTerms e = dem::energy(w);
      monitor.check_energy(w.time, balance(e), w.x.allFinite());
      if (row) push_rows(e);
    }
    if (w.max_overlap_ratio > 1) {
      monitor.flag("runaway overlap (a body passed through another) at t = " + fmt(w.time) + " s");
    }
    monitor.progress(k);
    if (ended_by_separation) break;
  }
  monitor.finish();
  const double cpu = cpu_seconds() - cpu0;
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  const double per_tick = seconds_per_tick(wall, ticks() - ticks0);

  result.status = monitor.status(im.first_contact_time >= 0);
  result.message = monitor.message();
  const double drift = monitor.drift();
  const std::string& unstable = monitor.message();
  auto& j = result.summary;
  j["status"] = result.status;
  if (!unstable.empty()) j["message"] = unstable;
  j["scene"] = s.name;
  j["model"] = "dem-spheres";
  j["contact_law"] = law_name(s.contact.law);
  j["recorded_body"] = s.bodies[s.record.body].name;
  j["peak_force"] = im.peak_force;
  j["impulse"] = im.impulse;
  j["contact_duration"] = im.duration_until(w.time);
  j["first_contact_time"] = im.first_contact_time < 0
                                ? nlohmann::ordered_json()
                                : nlohmann::ordered_json(im.first_contact_time);
  j["max_overlap"] = im.max_overlap;
  j["restitution"] =
      (w.record_contacts_ended > 0 && w.record_approach_speed > 0)
          ? nlohmann::ordered_json(w.record_separation_speed / w.record_approach_speed)
          : nlohmann::ordered_json();
  j["energy_drift"] = drift;
  // Oblique-impact rebound of the recorded sphere (run/rebound.hpp; Chung & Ooi tests 4–8).
  if (const std::optional<FirstImpact> impact = first_impact(s)) {
    auto motion = [&](int body) {
      BodyMotion m;
      for (int i = 0; i < w.size(); ++i) {
        if (w.body[i] == body) m = {.v = w.v.col(i), .w = w.w.col(i)};
      }
      return m;
    };
    add_rebound_measures(s, *impact, motion(s.record.body), motion(impact->partner),
                         w.record_contacts_ended > 0, j);
  }
  // The recorded sphere's final state (rebound and rolling checks); absent for a wall.
  for (int i = 0; i < w.size(); ++i) {
    if (w.body[i] != s.record.body) continue;
    const Vec3 v = w.v.col(i), om = w.w.col(i);
    j["final_velocity"] = {v.x(), v.y(), v.z()};
    j["final_speed"] = v.norm();
    j["final_angular_velocity"] = {om.x(), om.y(), om.z()};
  }
  j["dt"] = dt;
  j["dt_critical_predicted"] = crit.critical;
  j["dt_rayleigh"] = crit.rayleigh;
  j["dt_contact"] =
      std::isfinite(crit.contact) ? nlohmann::ordered_json(crit.contact) : nlohmann::ordered_json();
  j["dt_limited_by"] = crit.limited_by;
  j["dt_safety"] = given ? nlohmann::ordered_json()
                         : nlohmann::ordered_json(s.dt_safety.value_or(kSphereSafety));
  j["assumed_approach_speed"] = crit.approach_speed;
  j["steps"] = w.steps;
  j["simulated_time"] = w.time;
  j["ended_by"] = ended_by_separation ? "separation" : "duration";
  j["cpu_seconds"] = cpu;
  j["wall_seconds"] = wall;
  j["profile"] = {{"broad_phase", per_tick * static_cast<double>(w.profile.broad_phase)},
                  {"contact", per_tick * static_cast<double>(w.profile.contact)},
                  {"integrate", per_tick * static_cast<double>(w.profile.integrate)}};
  j["neighbour_rebuilds"] = w.rebuilds;
  j["contact_updates"] = w.contact_updates;
  j["damping"] = {{"form", s.contact.law == scene::ContactLaw::linear
                               ? "F = kn d + zeta sqrt(m* kn) d'"
                               : "F = K d^1.5 + zeta sqrt(m* K) d^0.25 d' (Tsuji form)"},
                  {"zeta_by_material_pair", [&] {
                     nlohmann::ordered_json z = nlohmann::ordered_json::object();
                     const int nm = static_cast<int>(w.materials.size());
                     for (int a = 0; a < nm; ++a)
                       for (int b = a; b < nm; ++b)
                         z[w.materials[a].name + "|" + w.materials[b].name] =
                             w.pair[a * nm + b].zeta;
                     return z;
                   }()}};
  return result;
}

using io::write_atomically;

void write_outputs(const RunResult& r, const std::filesystem::path& out) {
  std::filesystem::create_directories(out);
  if (r.status == "unstable") {
    // An unstable history is not a result: drop any earlier run's curves so none is mistaken
    // for this run's.
    std::filesystem::remove(out / "force.csv");
    std::filesystem::remove(out / "energy.csv");
  } else {
    std::ostringstream f;
    f.precision(10);
    f << "t,fx,fy,fz,f\n";
    for (const ForceRow& row : r.force) {
      f << row.t << ',' << row.fx << ',' << row.fy << ',' << row.fz << ',' << row.f << '\n';
    }
    write_atomically(out / "force.csv", f.str());
    std::ostringstream e;
    e.precision(10);
    e << "t,kinetic,elastic,contact,gravity,dissipated,total\n";
    for (const EnergyRow& row : r.energy) {
      e << row.t << ',' << row.kinetic << ',' << row.elastic << ',' << row.contact << ','
        << row.gravity << ',' << row.dissipated << ',' << row.total << '\n';
    }
    write_atomically(out / "energy.csv", e.str());
  }
  write_atomically(out / "summary.json", r.summary.dump(2) + "\n");
}

}  // namespace asperity::run
