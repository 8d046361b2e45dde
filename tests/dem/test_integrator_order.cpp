// Convergence in dt: the observed order of the peak-force error for an elastic Hertz impact.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "scenes/dem_scenes.hpp"
#include "solver/contact/hertz_impact.hpp"
#include "solver/core/material.hpp"
#include "solver/run/run_scene.hpp"

using namespace asperity;

TEST(IntegratorOrder, PeakForceErrorFallsAtSecondOrder) {
  const double v = 1.0;
  scene::SceneDef s = test::sphere_on_plane(v, 1e-4, scene::ContactLaw::hertz);
  const Material& m = s.materials[0];
  const double mass = m.density * 4.0 / 3.0 * M_PI * 1e-6;
  const contact::HertzImpact h = contact::hertz_impact(mass, 0.01, effective_young(m, m), v);
  // Contact starts exactly at t = 0 and dt = t_c / (2N) puts the exact peak on a step, so the
  // error left is the integrator's, not the sampling's (which is O(dt²) too but erratic).
  std::vector<double> dts, errors;
  for (int n : {10, 20, 40, 80}) {
    const double dt = h.contact_duration / (2 * n);
    const run::RunResult r =
        run::run_scene(s, {.dt = dt, .allow_unsafe_dt = true, .keep_rows = false});
    dts.push_back(dt);
    errors.push_back(std::abs(r.summary["peak_force"].get<double>() / h.peak_force - 1));
  }
  // Least-squares slope of log(error) against log(dt) over the four halvings.
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < dts.size(); ++k) {
    const double x = std::log(dts[k]), y = std::log(errors[k]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double nk = static_cast<double>(dts.size());
  const double order = (nk * sxy - sx * sy) / (nk * sxx - sx * sx);
  // Velocity Verlet is second order; 1.9–2.1 allows the higher-order terms at the coarsest step.
  EXPECT_GT(order, 1.9);
  EXPECT_LT(order, 2.1);
  // and each halving alone gains at least a factor 3.5 (4 in the asymptotic limit).
  for (std::size_t k = 1; k < errors.size(); ++k) EXPECT_GT(errors[k - 1] / errors[k], 3.5);
}
