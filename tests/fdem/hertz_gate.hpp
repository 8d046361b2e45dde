// The Hertz convergence gate (issue 11, item 2) for any sequence of levels of hertz_series.hpp:
// shared by test_hertz_convergence.cpp (label slow) and test_hertz_full.cpp (label hertz-full).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <vector>

#include "scenes/hertz_series.hpp"
#include "solver/core/richardson.hpp"
#include "validation/reference/finite_sphere.hpp"
#include "validation/reference/finite_sphere_dynamic.hpp"

namespace asperity::fdem::hertz {

inline const double kRatio = std::sqrt(2.0);  // refinement ratio between levels

struct Sequence {
  std::vector<Level> levels;  // coarsest first
  RichardsonRate peak, duration;
  RichardsonRate peak_filtered;  // of the peak after the T/20 moving average (hertz_series.hpp)
};

// Three whole-field levels (s falling by √2) at the block approach speed `speed`, printed as
// the table of reports/fem/hertz_convergence.md has them; `v` the variant (the elastic law).
inline Sequence sequence(Setup setup, double speed, std::initializer_list<double> scales,
                         const Variant& v = {}) {
  Sequence q;
  for (const double s : scales) {
    const Level l = hertz::run_level(setup, s, speed, true, v);
    EXPECT_TRUE(l.failure.empty()) << l.failure;
    std::printf(
        "%s a/R %.3f  s %.3f  h %.2f mm  tets %6ld  run %.1f s CPU  peak %+.4f (filtered %+.4f)  "
        "duration %+.4f  "
        "impulse/2mv %.4f  momentum/mv %.1e  (%ld steps, dt %.3g s)\n",
        setup == Setup::block ? "block" : "pair ", l.a_over_r, s, l.h * 1e3, l.tets, l.cpu,
        l.err_force, l.err_force_filtered, l.err_duration, l.impulse_ratio, l.momentum, l.steps,
        l.dt);
    std::fflush(stdout);
    q.levels.push_back(l);
  }
  const std::vector<Level>& l = q.levels;
  q.peak = richardson_rate(l[0].err_force, l[1].err_force, l[2].err_force, kRatio);
  q.duration = richardson_rate(l[0].err_duration, l[1].err_duration, l[2].err_duration, kRatio);
  q.peak_filtered = richardson_rate(l[0].err_force_filtered, l[1].err_force_filtered,
                                    l[2].err_force_filtered, kRatio);
  std::printf(
      "  order: peak %.2f, duration %.2f; finest level's own error: peak %+.4f, duration %+.4f; "
      "limit − Hertz: peak %+.4f, duration %+.4f; filtered peak: order %.2f, limit %+.4f\n",
      q.peak.order, q.duration.order, q.peak.finest_error, q.duration.finest_error, q.peak.limit,
      q.duration.limit, q.peak_filtered.order, q.peak_filtered.limit);
  return q;
}

// The convergence gate of test_hertz_convergence.cpp, for any sequence: errors falling at every
// level, an observed order above 0.75 (linear tetrahedra converge at first order or better in
// the contact compliance; below that the levels have stopped converging), the finest level
// within 2 % of the extrapolated limit (the 2 %, applied to what the solver controls),
// and the rebound impulse 2mv within 0.5 % (vibration keeps 0.01–0.02 % on these meshes).
// `filtered`: gate the peak after the T/20 moving average instead of the raw peak. The pair
// needs it: its deformable–deformable contact rings (raw peak 2.8 points above the filtered one
// at s = 1, and rising from s = √2 to 1 while the filtered peak and the duration fall).
// `own_error` false: the finest level's distance from the Richardson limit is printed, not gated
// (a sequence whose observed order is below 1 and whose next level is known not to follow the
// extrapolation: a/R = 0.15, test_hertz_convergence.cpp).
inline void expect_converges(const Sequence& q, const char* what, bool filtered = false,
                             bool own_error = true) {
  const std::vector<Level>& l = q.levels;
  const auto peak_error = [&](const Level& x) {
    return filtered ? x.err_force_filtered : x.err_force;
  };
  const RichardsonRate& peak = filtered ? q.peak_filtered : q.peak;
  for (std::size_t i = 1; i < l.size(); ++i) {
    EXPECT_LT(std::abs(peak_error(l[i])), std::abs(peak_error(l[i - 1]))) << what << " level " << i;
    EXPECT_LT(std::abs(l[i].err_duration), std::abs(l[i - 1].err_duration))
        << what << " level " << i;
  }
  for (const Level& x : l) EXPECT_NEAR(x.impulse_ratio, 1.0, 0.005) << what << " s " << x.s;
  EXPECT_GT(peak.order, 0.75) << what;
  EXPECT_GT(q.duration.order, 0.75) << what;
  if (!own_error) return;
  EXPECT_LT(std::abs(peak.finest_error), 0.02) << what;
  EXPECT_LT(std::abs(q.duration.finest_error), 0.02) << what;
}

// The finite sphere's impact at the sequence's mass and speed, as deviations from its own Hertz
// (the same E, ν, R, mass and speed as the 3D run's): the dynamic reference
// (validation/reference/finite_sphere_dynamic.hpp: a linear-elastic sphere with its inertia on a
// rigid frictionless plane, axisymmetric quadratic finite elements, implicit Newmark, nodal
// contact), which the gates hold the 3D runs against; and the quasi-static one
// (finite_sphere.hpp: the same sphere pressed by a d'Alembert body force, its law integrated as
// one degree of freedom), printed beside it. They differ by more than the 0.3 point that decides
// it at a/R = 0.107 (duration −3.31 against −3.71 %; reports/fem/finite_sphere_dynamic.md), and
// the 3D run is dynamic. Cost: about 5 s of CPU per mass and speed, cached.
struct FiniteSphere {
  double peak = 0;           // the dynamic reference's largest step-mean force (its raw peak)
  double peak_filtered = 0;  // its peak after the T/20 moving average, as the 3D runs filter
  double duration = 0;
  double quasi_static_peak = 0, quasi_static_duration = 0;
};
inline FiniteSphere finite_sphere(const Sequence& q) {
  const Material m = scenes::rubbery();
  const Level& l = q.levels.back();
  const reference::FiniteSphereDynamicImpact d = reference::finite_sphere_impact_dynamic_with_mass(
      m.young, m.poisson, l.mass, kRadius, l.speed);
  const reference::FiniteSphereImpact r =
      reference::finite_sphere_impact_with_mass(m.young, m.poisson, l.mass, kRadius, l.speed);
  return {.peak = d.step_mean_peak_force / d.hertz_peak_force - 1,
          .peak_filtered = d.filtered_peak_force / d.hertz_peak_force - 1,
          .duration = d.duration / d.hertz_duration - 1,
          .quasi_static_peak = r.peak_force / r.hertz_peak_force - 1,
          .quasi_static_duration = r.duration / r.hertz_duration - 1};
}

// The 2 %, held against the finite sphere instead of Hertz's half-space: the 3D
// Richardson limit within 2 % of the reference in peak force (filtered against filtered, raw
// against the reference's raw) and duration. What separates them besides the discretization: the
// 3D material is neo-Hookean, the reference linear (about −0.5 % on the peak at a/R = 0.107,
// reports/fem/finite_sphere.md).
inline void expect_matches_finite_sphere(const Sequence& q, const char* what,
                                         bool filtered = false) {
  const FiniteSphere f = finite_sphere(q);
  const double peak = filtered ? q.peak_filtered.limit : q.peak.limit;
  const double reference_peak = filtered ? f.peak_filtered : f.peak;
  std::printf(
      "  %s: limit − Hertz %+.4f / %+.4f, finite sphere − Hertz %+.4f / %+.4f (peak / "
      "duration; dynamic), quasi-static %+.4f / %+.4f\n",
      what, peak, q.duration.limit, reference_peak, f.duration, f.quasi_static_peak,
      f.quasi_static_duration);
  EXPECT_NEAR(peak, reference_peak, 0.02) << what;
  EXPECT_NEAR(q.duration.limit, f.duration, 0.02) << what;
}

// The 2 %, held level-wise: the finest level's own peak (T/20-filtered, and raw, which
// carries the ringing) and duration within 2 % of the finite sphere (its filtered and raw peaks
// respectively). For a sequence whose Richardson limit is not yet trustworthy (a/R = 0.15: the
// duration's observed order is below 1, so its extrapolation multiplies the last step by 2.7;
// reports/fem/hertz_convergence.md), this is what can be asserted: the solver's finest answer
// against an independent reference. The limit is printed beside it.
inline void expect_finest_matches_finite_sphere(const Sequence& q, const char* what) {
  const FiniteSphere f = finite_sphere(q);
  const Level& l = q.levels.back();
  std::printf(
      "  %s: finest level − Hertz: peak %+.4f (filtered %+.4f), duration %+.4f; finite sphere "
      "− Hertz (dynamic) %+.4f (filtered %+.4f) / %+.4f, quasi-static %+.4f / %+.4f; limits "
      "(filtered peak, duration) %+.4f / %+.4f\n",
      what, l.err_force, l.err_force_filtered, l.err_duration, f.peak, f.peak_filtered, f.duration,
      f.quasi_static_peak, f.quasi_static_duration, q.peak_filtered.limit, q.duration.limit);
  EXPECT_NEAR(l.err_force_filtered, f.peak_filtered, 0.02) << what << ": filtered peak";
  EXPECT_NEAR(l.err_force, f.peak, 0.02) << what << ": raw peak";
  EXPECT_NEAR(l.err_duration, f.duration, 0.02) << what << ": duration";
}

// Least-squares line y = c0 + c1 x with the standard errors of both coefficients from the
// residuals (n > 2; NaN otherwise).
struct Line {
  double c0 = 0, c1 = 0, se0 = 0, se1 = 0;
};
inline Line fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < x.size(); ++i) mx += x[i] / n, my += y[i] / n;
  double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
  }
  Line l{.c1 = sxy / sxx};
  l.c0 = my - l.c1 * mx;
  double ss = 0;
  for (std::size_t i = 0; i < x.size(); ++i) ss += std::pow(y[i] - l.c0 - l.c1 * x[i], 2);
  const double s2 = x.size() > 2 ? ss / (n - 2) : std::nan("");
  l.se0 = std::sqrt(s2 * (1 / n + mx * mx / sxx));
  l.se1 = std::sqrt(s2 / sxx);
  return l;
}

}  // namespace asperity::fdem::hertz
