// One level of the Hertz convergence sequences (issue 11, item 2), shared by the gates
// (test_hertz_convergence.cpp) and the benchmark of the finest level (benchmarks/hertz_bench.cpp):
// the sphere of hertz_spheres.hpp on a fixed block, or two of them head-on, at a given contact
// size a/R and whole-field refinement scale s, run once to the end of the contact.
#pragma once

#include <algorithm>
#include <cmath>
#include <ctime>
#include <numbers>
#include <string>
#include <vector>

#include "scenes/hertz_spheres.hpp"

namespace asperity::fdem::hertz {

enum class Setup { block, pair };

// The block approach speed whose Hertz contact radius is a/R (nominal sphere mass): δ = (a/R)² R,
// v = √(16 E* √R δ^{5/2} / (15 m)) (Johnson 1985 §11.4 solved for v). 0.2 m/s gives a/R = 0.107.
inline double speed_for(double a_over_r, const Material& m) {
  const double e_star = m.young / (1 - m.poisson * m.poisson);
  const double mass = m.density * 4.0 / 3.0 * std::numbers::pi * std::pow(kRadius, 3);
  const double d = a_over_r * a_over_r * kRadius;
  return std::sqrt(16 * e_star * std::sqrt(kRadius) * std::pow(d, 2.5) / (15 * mass));
}

// The contact radius relative to that at kSpeed: a ∝ δ^{1/2} ∝ v^{2/5}. Everything that
// resolves the contact (element size at the strike point and the zone where it holds, the
// surface facets and their patch) scales with it, so every a/R sees the same elements per contact
// radius and the same sagitta/approach (0.7 %); the far field (growth, cap) is the sphere's bulk
// and does not. At kSpeed the scale is 1: the level of the original gate, unchanged.
inline double contact_scale(double speed) {
  return std::pow(speed / kSpeed, 0.4);
}

// Whole-field refinement level s at contact scale k: size 4sk mm at the strike point, constant
// within 20k mm of it, growing at 0.15s beyond, up to 12.5s mm (graded); or 8sk mm everywhere
// (uniform: the cost comparison). Facets 2.5k mm within 30k mm of the strike point either way.
inline double level_size(double s, double k, bool graded) {
  return (graded ? 0.004 : 0.008) * s * k;
}
inline TetMesh level_mesh(double s, double k, bool graded = true) {
  geometry::TetOptions o;
  o.radius_edge_ratio = 1.5;
  o.element_size =
      element_size(level_size(s, k, graded), graded, kRadius, 0.15 * s, 0.0125 * s, 0.02 * k);
  return geometry::tetrahedralize(sphere_surface(kRadius, kGeometryEdge * k, kGeometryPatch * k),
                                  o);
}

// The pair: the sphere (strike point down) above z = 0 moving down at `speed`, and its mirror
// image through z = 0 moving up at `speed`: relative speed 2v, the mid-plane a frictionless
// plane of symmetry, so each sphere sees the block case at v. Hertz for the pair (m* = m/2,
// R* = R/2, E* = E/(2(1 − ν²)), relative speed 2v) is the block's at v: the same peak force,
// duration and contact radius, twice the total approach.
inline WorldDef sphere_pair(const TetMesh& ball, const Material& m, double speed, double gap,
                            double alpha = 10) {
  WorldDef def =
      scenes::mirrored_pair(scenes::translated(ball, Vec3(0, 0, kRadius + gap / 2)), m, speed);
  def.contact.alpha = alpha;
  return def;
}

struct Level {
  Setup setup = Setup::block;
  double s = 0;                         // refinement scale: every element size × s
  double a_over_r = 0;                  // Hertz contact radius / R of this impact
  double h = 0;                         // m, element size at the strike point
  long tets = 0, nodes = 0, steps = 0;  // tets and nodes of one sphere
  double dt = 0;
  std::string limited_by;
  double peak = 0, duration = 0;  // N, s
  double err_force = 0, err_duration = 0;
  // The peak after a centred moving average over a twentieth of the contact (the filter of
  // run/impact_measures.hpp: lowers a Hertz pulse's peak by about 0.17 %), and its error: what of
  // the raw peak is ringing.
  double peak_filtered = 0, err_force_filtered = 0;
  double mass = 0;           // kg, one sphere's (the meshed volume's: the same at every level)
  double speed = 0;          // m/s, the block approach speed (each sphere's in the pair)
  double impulse_ratio = 0;  // body 0's velocity change / 2v: 1 for an elastic rebound
  double momentum = 0;       // |total momentum| / (m v) at the end (pair; 0 for the block)
  double cpu = 0;            // s, std::clock of the run (not the meshing, not the set-up)
  double setup_cpu = 0;      // s, std::clock of make_world and the critical step
  double evaluations = 0;    // contact pairs through the kernel per step
  double contact_share = 0;  // share of the profiled step time in broad and narrow phase
  double max_rotation = 0;   // linear law: the largest element rotation (sin θ; 0 neo-Hookean)
  std::string failure;
};

// What a level may vary besides s: the penalty α (item 3 of issue 11: the peak independent of α
// at the converged level), the step as a fraction of the predicted critical step, and the contact
// zone's scale (> 0 replaces contact_scale(speed) for the mesh: the a/R = 0.15 sequence on a finer
// contact zone, reports/fem/hertz_convergence.md).
// The elastic law: neo-Hookean (the default) or small-strain linear, the law of Hertz's theory and
// of the finite-sphere reference (the material's own effect apart from the discretization's).
struct Variant {
  double alpha = 10;
  double dt_safety = 0.5;
  double zone_scale = 0;
  ElasticLaw law = ElasticLaw::neo_hookean;
};

// One impact at refinement s, block approach speed `speed`, α = 10, dt = 0.5 × the predicted
// critical step unless `v` says otherwise, no energy bookkeeping (it would double a step's cost).
// The peak is the raw peak (ringing 0.3–0.9 % of Hertz at α = 10,
// reports/fem/hertz_convergence.md), the duration the time with a non-zero contact force on body 0.
inline Level run_level(Setup setup, double s, double speed = kSpeed, bool graded = true,
                       const Variant& v = {}) {
  Material m = scenes::rubbery();
  m.law = v.law;
  const double k = v.zone_scale > 0 ? v.zone_scale : contact_scale(speed);
  const TetMesh ball = level_mesh(s, k, graded);
  const scenes::Hertz ref = sphere_on_block_hertz(ball, m, speed);
  // The initial clearance, 0.17 of the approach (0.2 mm at kSpeed), scales with it.
  const double gap = 2e-4 * k * k;
  const std::clock_t t0 = std::clock();
  World w = make_world(setup == Setup::block ? sphere_on_block(ball, m, v.alpha, speed, gap)
                                             : sphere_pair(ball, m, speed, gap, v.alpha));
  const CriticalStep cs = critical_step(w);
  const double dt = v.dt_safety * cs.critical;
  const std::clock_t t1 = std::clock();
  const double v_before = body_velocity(w, 0).z();
  double peak = 0, duration = 0;
  std::vector<double> history;
  bool touched = false;
  while (w.time < 0.2 && w.failure.empty()) {
    w.want_energy = false;
    step(w, dt);
    const double f = w.contacts.force.col(0).norm();
    peak = std::max(peak, f);
    if (f > 0) {
      touched = true;
      duration += dt;
    } else if (touched && body_velocity(w, 0).z() * v_before < 0) {
      break;  // the force is zero and body 0 moves away: the contact is over
    }
    // A stiff penalty (α = 100) chatters: the force drops to zero for a step or two while the
    // sphere still approaches, so a zero force ends the contact only on the rebound, the gaps stay
    // in the filter's history as zeros, and the duration counts only the steps with a force (the
    // same as before at α = 10 and 30, which do not chatter).
    if (touched) history.push_back(f);
  }
  while (!history.empty() && history.back() == 0) history.pop_back();
  const double mass = w.bodies[0].mass;
  const std::size_t n = history.size(), win = std::max<std::size_t>(1, n / 20);
  double sum = 0, filtered = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sum += history[i] - (i >= win ? history[i - win] : 0.0);
    if (i + 1 >= win) filtered = std::max(filtered, sum / static_cast<double>(win));
  }
  return {.setup = setup,
          .s = s,
          .a_over_r = std::sqrt(ref.overlap * kRadius) / kRadius,
          .h = level_size(s, k, graded),
          .tets = ball.tets.cols(),
          .nodes = ball.nodes.cols(),
          .steps = w.steps,
          .dt = dt,
          .limited_by = cs.limited_by,
          .peak = peak,
          .duration = duration,
          .err_force = peak / ref.force - 1,
          .err_duration = duration / ref.duration - 1,
          .peak_filtered = filtered,
          .err_force_filtered = filtered / ref.force - 1,
          .mass = w.bodies[0].mass,
          .speed = speed,
          .impulse_ratio = (body_velocity(w, 0).z() - v_before) / (-2 * v_before),
          .momentum = setup == Setup::pair ? momentum(w).norm() / (mass * speed) : 0,
          .cpu = static_cast<double>(std::clock() - t1) / CLOCKS_PER_SEC,
          .setup_cpu = static_cast<double>(t1 - t0) / CLOCKS_PER_SEC,
          .evaluations = static_cast<double>(w.contact_evaluations) / static_cast<double>(w.steps),
          .contact_share = static_cast<double>(w.profile.contact + w.profile.broad_phase) /
                           static_cast<double>(w.profile.total()),
          .max_rotation = w.max_rotation,
          .failure = w.failure};
}

}  // namespace asperity::fdem::hertz
