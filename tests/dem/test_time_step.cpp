// The predicted critical step: stable just below it, unstable above it (linear law, where the
// central-difference limit 2/ω is exact).
#include <cmath>

#include <gtest/gtest.h>

#include "scenes/dem_scenes.hpp"
#include "solver/core/error.hpp"
#include "solver/run/run_scene.hpp"

using namespace asperity;

namespace {
scene::SceneDef linear_scene() {
  scene::SceneDef s = test::sphere_on_plane(1.0, 2e-3, scene::ContactLaw::linear);
  s.contact.kn = 1e7;
  return s;
}
}  // namespace

TEST(TimeStep, LinearContactStepIsTwoOverOmega) {
  const scene::SceneDef s = linear_scene();
  const run::RunResult r = run::run_scene(s, {.keep_rows = false});
  const double m = 2500 * 4.0 / 3.0 * M_PI * 1e-6;
  // Predicted contact limit uses m* = m/2 (the conservative sphere–sphere bound): 2√(m/(2 kn)).
  EXPECT_NEAR(r.summary["dt_contact"].get<double>(), 2 * std::sqrt(0.5 * m / 1e7), 1e-15);
}

TEST(TimeStep, StableAtHalfAndUnstableAboveTheExactLimit) {
  const scene::SceneDef s = linear_scene();
  const double m = 2500 * 4.0 / 3.0 * M_PI * 1e-6;
  const double exact = 2 * std::sqrt(m / 1e7);  // sphere on a fixed plane: m* = m
  const run::RunResult below =
      run::run_scene(s, {.dt = 0.5 * exact, .allow_unsafe_dt = true, .keep_rows = false});
  // At ω dt = 1 the leapfrog energy oscillates by a third at most ((1 − (ω dt/2)²)⁻¹) and stays
  // bounded: below the 50 % growth that flags instability.
  EXPECT_EQ(below.status, "ok");
  // Past ω dt = 2 the leapfrog amplification factor exceeds one: the overlap grows each step
  // until the sphere passes through the plane or the energy explodes.
  scene::SceneDef longer = s;
  longer.duration = 0.05;
  const run::RunResult above =
      run::run_scene(longer, {.dt = 1.2 * exact, .allow_unsafe_dt = true, .keep_rows = false});
  EXPECT_EQ(above.status, "unstable");
}

TEST(TimeStep, GivenStepAboveThePredictionIsRefused) {
  scene::SceneDef s = linear_scene();
  s.dt = 1e-3;
  EXPECT_THROW(run::run_scene(s), InputError);
}
