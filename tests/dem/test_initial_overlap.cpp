// A sphere scene that starts pressed (scene key allow_initial_overlap): refused without the key,
// with a message that names it; with it, the stored Hertz energy is what drives the bodies apart.
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "scenes/dem_scenes.hpp"
#include "solver/core/error.hpp"
#include "solver/core/material.hpp"
#include "solver/run/run_scene.hpp"

using namespace asperity;

namespace {

constexpr double kRadius = 0.01;  // m
constexpr double kPress = 1e-5;   // starting overlap δ₀, m (a thousandth of the radius)

// Two glass spheres at rest, centres 2r − δ₀ apart; elastic (e = 1) and frictionless, no gravity.
scene::SceneDef pressed_pair() {
  scene::SceneDef s;
  s.name = "pressed-pair";
  s.duration = 1e-4;  // many times the release, which lasts about a third of a Hertz period
  s.materials = {test::glass()};
  const double half = kRadius - 0.5 * kPress;
  s.bodies = {{.name = "a",
               .material = 0,
               .shape = scene::SphereShape{.radius = kRadius},
               .position = Vec3(0, 0, half)},
              {.name = "b",
               .material = 0,
               .shape = scene::SphereShape{.radius = kRadius},
               .position = Vec3(0, 0, -half)}};
  s.contact.law = scene::ContactLaw::hertz;
  s.record = {.body = 0, .every = 1};
  return s;
}

std::string refusal(const scene::SceneDef& s) {
  try {
    run::run_scene(s, {.keep_rows = false});
  } catch (const InputError& e) {
    return e.what();
  }
  return "(ran)";
}

}  // namespace

TEST(InitialOverlap, IsRefusedWithAMessageNamingTheKey) {
  const std::string pair = refusal(pressed_pair());
  EXPECT_NE(pair.find("\"a\": position: starts overlapping \"b\""), std::string::npos) << pair;
  EXPECT_NE(pair.find("allow_initial_overlap"), std::string::npos) << pair;

  scene::SceneDef on_plane = pressed_pair();
  on_plane.bodies[1] = {.name = "floor",
                        .material = 0,
                        .shape = scene::PlaneShape{.point = Vec3::Zero(), .normal = Vec3::UnitZ()},
                        .fixed = true};
  on_plane.bodies[0].position = Vec3(0, 0, kRadius - kPress);
  const std::string plane = refusal(on_plane);
  EXPECT_NE(plane.find("starts inside \"floor\""), std::string::npos) << plane;
  EXPECT_NE(plane.find("allow_initial_overlap"), std::string::npos) << plane;
}

// Released from δ₀ at rest, the pair leaves with the Hertz energy U₀ = 8/15 E* √R* δ₀^{5/2}
// (contact/hertz.hpp) as kinetic energy, 2 · ½ m v² = U₀ (energy conservation, no damping).
TEST(InitialOverlap, PressedPairSeparatesWithItsStoredHertzEnergy) {
  scene::SceneDef s = pressed_pair();
  s.allow_initial_overlap = true;
  const run::RunResult r = run::run_scene(s, {.keep_rows = false});
  ASSERT_EQ(r.status, "ok") << r.message;

  const Material& glass = s.materials[0];
  const double e_star = effective_young(glass, glass), r_star = 0.5 * kRadius;
  const double m = glass.density * 4.0 / 3.0 * std::numbers::pi * std::pow(kRadius, 3);
  const double u0 = 8.0 / 15.0 * e_star * std::sqrt(r_star) * std::pow(kPress, 2.5);
  const double v_exact = std::sqrt(u0 / m);
  // Velocity Verlet holds a harmonic oscillator's energy within (ω dt)²/4 relative; ω from the
  // Hertz tangent stiffness at δ₀ (the stiffest point of the release), m* = m/2. Allowed: (ω dt)²,
  // four times that bound for the stiffening of the Hertz law; the speed's error is half the
  // energy's.
  const double k_max = 2.0 * e_star * std::sqrt(r_star * kPress);
  const double omega_dt = std::sqrt(k_max / (0.5 * m)) * r.summary.at("dt").get<double>();
  const auto& v = r.summary.at("final_velocity");
  EXPECT_NEAR(v[2].get<double>(), v_exact, 0.5 * omega_dt * omega_dt * v_exact)
      << "omega dt " << omega_dt;
  EXPECT_EQ(v[0].get<double>(), 0.0);  // a head-on release stays on its axis
  EXPECT_EQ(v[1].get<double>(), 0.0);
}
