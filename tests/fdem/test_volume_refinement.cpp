// Faceted rigid spheres under volume-hertz against Hertz, by facet refinement: on a plane and on
// another sphere, the peak force and the contact duration converge to the smooth sphere's answer
// under the same law (asserted as a falling error), which is Hertz's to O(δ/R) (asserted within
// the 3 %); every impact is elastic (restitution 1 ± 1e-3) and keeps its energy (1e-3).
// Measured (plane; two spheres), errors against the smooth sphere at n = 8, 16, 32:
//   peak     −2.8 %, +0.32 %, +0.02 %;   +10.5 %, +0.83 %, +0.12 %
//   duration +10.0 %, +2.4 %, +0.61 %;   +21.0 %, +5.6 %, +1.4 %   (order 2 in the facet size)
// restitution 1 − e < 1e-6, energy drift < 2e-5. Label "slow": about 8 s of CPU (the 20,480-face
// spheres).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "scenes/volume_scenes.hpp"

namespace asperity::fdem {
namespace {

namespace vs = volume_scenes;

// R = 0.05 m, E = 1e7 Pa, ρ = 2500: at v = 0.18 m/s the peak approach is δ ≈ 0.02 R, where the
// contact disc (a ≈ 0.2 R) spans 3, 6 and 12 facets at frequencies 8, 16 and 32 and the law's
// departure from Hertz, 7δ/(12R) in force at equal δ, is about 1 %.
constexpr double kR = 0.05, kV = 0.18;

struct Errors {
  double force = 0, duration = 0;
};

Errors run_on_plane(int n, const vs::SmoothImpact& ref, double& e_out, double& drift_out) {
  const Material m = vs::stone();
  WorldDef def;
  def.bodies.push_back({.name = "ball",
                        .kind = BodyKind::rigid,
                        .mesh = vs::faceted_sphere(kR, n, Vec3(0, 0, kR + 2e-4)),
                        .material = m,
                        .velocity = Vec3(0, 0, -kV)});
  def.bodies.push_back(vs::block(kR, m));
  def.contact.law = ContactLaw::volume_hertz;
  World w = make_world(def);
  const vs::Impact im = vs::run_impact(w, 1.0);
  e_out = -im.v_after.z() / im.v_before.z();
  drift_out = im.drift;
  return {im.peak_force / ref.peak_force - 1, im.duration / ref.duration - 1};
}

Errors run_two_spheres(int n, const vs::SmoothImpact& ref, double& e_out, double& drift_out) {
  const Material m = vs::stone();
  WorldDef def;
  def.bodies.push_back({.name = "left",
                        .kind = BodyKind::rigid,
                        .mesh = vs::faceted_sphere(kR, n, Vec3(-kR - 1e-4, 0, 0)),
                        .material = m,
                        .velocity = Vec3(kV / 2, 0, 0)});
  def.bodies.push_back({.name = "right",
                        .kind = BodyKind::rigid,
                        .mesh = vs::faceted_sphere(kR, n, Vec3(kR + 1e-4, 0, 0)),
                        .material = m,
                        .velocity = Vec3(-kV / 2, 0, 0)});
  def.contact.law = ContactLaw::volume_hertz;
  World w = make_world(def);
  const vs::Impact im = vs::run_impact(w, 1.0);
  e_out = -(im.v_after.x() - body_velocity(w, 1).x()) / kV;
  drift_out = im.drift;
  return {im.peak_force / ref.peak_force - 1, im.duration / ref.duration - 1};
}

struct Hertz {
  double force, duration;
};
Hertz hertz(double m, double r, double e_star, double v) {
  const double d = std::pow(15 * m * v * v / (16 * e_star * std::sqrt(r)), 0.4);
  return {4.0 / 3.0 * e_star * std::sqrt(r) * std::pow(d, 1.5), 2.9432 * d / v};
}

void check_sequence(bool two_spheres) {
  const Material m = vs::stone();
  const double mass = m.density * 4.0 / 3.0 * std::numbers::pi * kR * kR * kR;
  const double e_plane = 1.0 / (2 * (1 - m.poisson * m.poisson) / m.young);
  const double m_star = two_spheres ? mass / 2 : mass, r_star = two_spheres ? kR / 2 : kR;
  const vs::SmoothImpact ref =
      vs::smooth_sphere_impact(kR, m_star, kV, e_plane, r_star, two_spheres);
  const Hertz h = hertz(m_star, r_star, e_plane, kV);
  std::printf("smooth sphere under the law against Hertz: peak %+.4f, duration %+.4f\n",
              ref.peak_force / h.force - 1, ref.duration / h.duration - 1);
  // The smooth sphere under the law is Hertz's to O(δ/R): within 1.5 % here.
  EXPECT_NEAR(ref.peak_force / h.force, 1.0, 0.015);
  EXPECT_NEAR(ref.duration / h.duration, 1.0, 0.015);
  double prev_f = 1e300, prev_t = 1e300;
  Errors last;
  for (const int n : {8, 16, 32}) {
    double e = 0, drift = 0;
    const Errors err =
        two_spheres ? run_two_spheres(n, ref, e, drift) : run_on_plane(n, ref, e, drift);
    std::printf(
        "n = %d: peak %+.4f, duration %+.4f against the smooth sphere; e = %.6f, drift %.2e\n", n,
        err.force, err.duration, e, drift);
    EXPECT_NEAR(e, 1.0, 1e-3) << "n = " << n;
    EXPECT_LT(drift, 1e-3) << "n = " << n;
    // Convergence: each refinement at least halves the larger of the two errors' bound (the
    // facet error is O(h²/δ), a factor 4 per doubling; 2 leaves room for where the facets fall).
    const double ef = std::abs(err.force), et = std::abs(err.duration);
    if (n > 8) {
      EXPECT_LT(ef, std::max(prev_f / 2, 2e-3)) << "n = " << n;
      EXPECT_LT(et, std::max(prev_t / 2, 2e-3)) << "n = " << n;
    }
    prev_f = ef, prev_t = et;
    last = err;
  }
  // The finest within the 3 % of Hertz itself.
  EXPECT_LT(std::abs((1 + last.force) * ref.peak_force / h.force - 1), 0.03);
  EXPECT_LT(std::abs((1 + last.duration) * ref.duration / h.duration - 1), 0.03);
}

TEST(VolumeHertzRefinement, FacetedSphereOnPlane) {
  check_sequence(false);
}

TEST(VolumeHertzRefinement, TwoFacetedSpheres) {
  check_sequence(true);
}

}  // namespace
}  // namespace asperity::fdem
