// Friction under volume-hertz (fdem/volume_contact.cpp, volume_friction): a faceted rigid sphere
// striking a plane obliquely with Coulomb friction against the smooth rigid sphere under
// Hertz–Mindlin (dem/sphere_world.cpp, contact/hertz_mindlin.hpp), the law volume-hertz reduces to
// on a sphere: Hertz's normal force and Mindlin's k_t = 8 G* a. Elastic in both (no damping), so
// the rebound's tangential velocity and spin are set by the stick and slip of the tangential spring
// alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "scenes/volume_scenes.hpp"
#include "solver/dem/sphere_world.hpp"
#include "solver/dem/time_step.hpp"

namespace asperity::fdem {
namespace {

namespace vs = volume_scenes;

// R = 0.05 m, E = 1e7 Pa (peak δ ≈ 0.02 R, as the refinement test), μ = 0.3. The incidence
// v_t / (μ v_n) = 1.85 lies between gross sliding (> 3.5 for these materials, where the result
// is μ's alone) and rolling: the contact sticks, then slips, and the rebound depends on k_t's
// history (Maw, Barber & Fawcett 1976; Thornton & Yin 1991), which is what is compared.
constexpr double kR = 0.05, kVn = 0.18, kVt = 0.1, kMu = 0.3;

Material stone() {
  Material m = vs::stone();
  m.friction = kMu;
  return m;
}

struct Rebound {
  double vt = 0, spin = 0;  // tangential velocity of the centre (m/s), spin ω_y R (m/s)
};

// The smooth sphere under Hertz–Mindlin at 1/100 of its critical step, restitution 1.
Rebound hertz_mindlin(double& drift) {
  const Material m = stone();
  dem::SphereWorld w;
  w.materials = {m};
  w.law.normal = contact::NormalLaw::hertz;
  w.law.tangential = true;
  w.law.restitution = 1.0;
  const double mass = m.density * 4.0 / 3.0 * std::numbers::pi * kR * kR * kR;
  w.radius = {kR}, w.mass = {mass}, w.inertia = {0.4 * mass * kR * kR};
  w.material = {0}, w.body = {0}, w.fixed = {0};
  w.walls.push_back({.kind = dem::WallKind::plane,
                     .a = Vec3::Zero(),
                     .b = Vec3::UnitZ(),
                     .material = 0,
                     .body = 1});
  w.x = Vec3(0, 0, kR + 1e-6);
  w.v = Vec3(kVt, 0, -kVn);
  w.w = Vec3::Zero();
  dem::initialise(w);
  const double dt = 0.01 * dem::critical_step(w).critical;
  const double e0 = dem::energy(w).total();
  bool touched = false;
  while (w.time < 1.0) {
    dem::step(w, dt);
    drift = std::max(drift, std::abs(dem::energy(w).total() - e0) / e0);
    const bool touching = w.contacts.force.col(0).norm() > 0;
    if (touched && !touching) break;
    touched = touched || touching;
  }
  return {w.v(0, 0), w.w(1, 0) * kR};
}

// The faceted sphere (geodesic frequency n) under volume-hertz with friction; also its energy
// drift (the balance with the friction work in `dissipated`).
Rebound faceted(int n, double& drift) {
  WorldDef def;
  def.bodies.push_back({.name = "ball",
                        .kind = BodyKind::rigid,
                        .mesh = vs::faceted_sphere(kR, n, Vec3(0, 0, kR + 2e-4)),
                        .material = stone(),
                        .velocity = Vec3(kVt, 0, -kVn)});
  def.bodies.push_back(vs::block(kR, stone()));
  def.contact.law = ContactLaw::volume_hertz;
  def.contact.friction = kMu;
  World w = make_world(def);
  const vs::Impact im = vs::run_impact(w, 1.0);
  drift = im.drift;
  return {im.v_after.x(), w.rigid[0].omega.y() * kR};
}

// Measured: Hertz–Mindlin v_t' = 0.06991 m/s, ω R = 0.07452 m/s; the faceted sphere at n = 8, 16
// (1,280 and 5,120 faces) differs by −0.48 %, −0.30 % of v_t in v_t' and +1.6 %, +0.46 % in ω R.
// Asserted: within 1 % of v_t at n = 16 (the facets' own error in the force history, +0.3 % in
// peak force and +2.4 % in duration at n = 16 in the refinement test, plus the law's O(δ/R) ≈ 1 %
// departure from Hertz, which does not refine away), and the spin's error at least halved from
// n = 8 to 16 (order 2 in the facet size: a factor 4; measured 3.6). Energy: the friction work is
// booked as in Hertz–Mindlin, whose incremental spring with a stiffness that changes with the
// overlap is not exactly a potential (its |F_s|²/2k_t is not the work done on it): the smooth
// sphere's own balance drifts 1.21e-2 here, the faceted one's 0.95e-2 and 1.24e-2; asserted no
// more than 1e-3 above the reference's. Label slow: 1.2 s.
TEST(VolumeHertzFriction, ObliqueFacetedSphereMatchesHertzMindlin) {
  double ref_drift = 0;
  const Rebound ref = hertz_mindlin(ref_drift);
  std::printf("Hertz–Mindlin: v_t' = %.6f m/s, ω R = %.6f m/s, drift %.2e\n", ref.vt, ref.spin,
              ref_drift);
  double prev_spin_error = 0;
  for (const int n : {8, 16}) {
    double drift = 0;
    const Rebound r = faceted(n, drift);
    const double e_vt = (r.vt - ref.vt) / kVt, e_spin = (r.spin - ref.spin) / kVt;
    std::printf("n = %d: v_t' = %.6f (%+.2e of v_t), ω R = %.6f (%+.2e of v_t), drift %.2e\n", n,
                r.vt, e_vt, r.spin, e_spin, drift);
    EXPECT_LT(drift, ref_drift + 1e-3) << "n = " << n;
    if (n == 16) {
      EXPECT_LT(std::abs(e_vt), 0.01);
      EXPECT_LT(std::abs(e_spin), 0.01);
      EXPECT_LT(std::abs(e_spin), prev_spin_error / 2);
    }
    prev_spin_error = std::abs(e_spin);
  }
}

}  // namespace
}  // namespace asperity::fdem
