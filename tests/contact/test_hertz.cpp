// Hertz normal law and the closed-form impact against their formulas (Johnson 1985).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "solver/contact/hertz.hpp"
#include "solver/contact/hertz_impact.hpp"

using namespace asperity::contact;

TEST(Hertz, ElasticForceStiffnessAndEnergyMatchTheFormula) {
  const HertzParams p{.young_eff = 3.0e10, .radius_eff = 0.005, .mass_eff = 0.01, .zeta = 0};
  const double d = 2e-5;
  const NormalForce f = hertz_normal(d, 0.0, p);
  const double k = 4.0 / 3.0 * 3.0e10 * std::sqrt(0.005);
  // Round-off only: the same products in another order.
  EXPECT_NEAR(f.force, k * std::pow(d, 1.5), 1e-12 * f.force);
  EXPECT_NEAR(f.stiffness, 1.5 * k * std::sqrt(d), 1e-12 * f.stiffness);
  EXPECT_NEAR(f.energy, 0.4 * k * std::pow(d, 2.5), 1e-12 * f.energy);
  // dU/dδ = F and dF/dδ = S: central differences, truncation error O(h²) ~ 1e-8 relative.
  const double h = 1e-9;
  const double dU = (hertz_normal(d + h, 0, p).energy - hertz_normal(d - h, 0, p).energy) / (2 * h);
  const double dF = (hertz_normal(d + h, 0, p).force - hertz_normal(d - h, 0, p).force) / (2 * h);
  EXPECT_NEAR(dU, f.force, 1e-6 * f.force);
  EXPECT_NEAR(dF, f.stiffness, 1e-6 * f.stiffness);
}

TEST(Hertz, DampedForceIsClippedAtZeroWhileSeparating) {
  const HertzParams p{.young_eff = 3.0e10, .radius_eff = 0.005, .mass_eff = 0.01, .zeta = 1.0};
  const NormalForce f = hertz_normal(1e-7, -5.0, p);  // tiny overlap, fast separation
  EXPECT_LT(f.elastic + f.damping, 0.0);
  EXPECT_EQ(f.force, 0.0);  // no cohesion: the law never pulls
}

TEST(HertzImpact, EnergyBalanceAtPeakOverlap) {
  // At δ_max the approach kinetic energy ½ m* v² is all stored: 8/15 E* √R* δ_max^{5/2}.
  const double m = 0.0052, r = 0.005, e = 3.3e10, v = 1.0;
  const HertzImpact h = hertz_impact(m, r, e, v);
  const double stored = 8.0 / 15.0 * e * std::sqrt(r) * std::pow(h.max_overlap, 2.5);
  EXPECT_NEAR(stored, 0.5 * m * v * v, 1e-12 * stored);
  // Duration scales as v^{-1/5} (Johnson 1985, eq. 11.24).
  const HertzImpact h10 = hertz_impact(m, r, e, 10 * v);
  EXPECT_NEAR(h10.contact_duration / h.contact_duration, std::pow(10.0, -0.2), 1e-12);
}

TEST(HertzImpact, DurationFactorIsTheBetaFunctionIntegral) {
  // 2∫₀¹ (1 − x^{5/2})^{-1/2} dx = (4/5) B(2/5, 1/2), evaluated through lgamma.
  const double beta = std::exp(std::lgamma(0.4) + std::lgamma(0.5) - std::lgamma(0.9));
  EXPECT_NEAR(kHertzDurationFactor, 0.8 * beta, 1e-10);
}

TEST(HertzImpact, ContactTimeIsJohnsonsClosedForm) {
  // Johnson (1985, §11.4): t_c = 2.868 (m²/(R E*² v))^{1/5}, here for a glass sphere (R = 1 cm,
  // m = 2500·4/3πR³, E* = 30 GPa) on a rigid plane at 1 m/s. 2.868 is the book's constant to
  // four figures (2.9432·(15/16)^{2/5} = 2.86818), so 2e-4 of it is the rounding's bound.
  const double r = 0.01, m = 2500 * 4.0 / 3 * std::numbers::pi * r * r * r;
  const double johnson = 2.868 * std::pow(m * m / (r * 3e10 * 3e10 * 1.0), 0.2);
  EXPECT_NEAR(hertz_contact_time(m, r, 3e10, 1.0) / johnson, 1.0, 2e-4);
  // Slower impacts last longer: t ∝ v^(−1/5), so 32 times faster halves it.
  EXPECT_NEAR(hertz_contact_time(m, r, 3e10, 32.0) / hertz_contact_time(m, r, 3e10, 1.0), 0.5,
              1e-12);
}

TEST(HertzContact, AtTheImpactsPeakItIsTheOverlapsCircle) {
  // At the peak of an impact the static Hertz contact holds: δ_max = a² / R* (Johnson 1985, §4.2)
  // and the pressure p0 √(1 − r²/a²) integrates to F = (2/3) π a² p0. Both hold to
  // round-off (a cube root, a power 0.4 and 1.5): 1e-13 relative.
  const double m = 0.0052, r = 0.005, e = 3.3e10, v = 1.0;
  const HertzImpact h = hertz_impact(m, r, e, v);
  const HertzContact c = hertz_contact(h.peak_force, r, e);
  EXPECT_NEAR(c.radius * c.radius / r / h.max_overlap, 1.0, 1e-13);
  EXPECT_NEAR(2.0 / 3.0 * std::numbers::pi * c.radius * c.radius * c.peak_pressure / h.peak_force,
              1.0, 1e-13);
  // a grows as F^{1/3}: eight times the force doubles it.
  EXPECT_NEAR(hertz_contact(8 * h.peak_force, r, e).radius / c.radius, 2.0, 1e-13);
}

TEST(HertzContact, PressureIsTheEllipseUnderTheCircle) {
  // p(r) = p0 √(1 − r²/a²) (Johnson 1985, §4.2): p0 at the centre, √3/2 p0 halfway, none
  // from the rim on; halfway to a few roundings (a quotient, a square root, a product): 1e-15.
  const HertzContact c = hertz_contact(100.0, 0.05, 1e7);
  EXPECT_EQ(hertz_pressure(c, 0.0), c.peak_pressure);
  EXPECT_NEAR(hertz_pressure(c, 0.5 * c.radius) / c.peak_pressure, std::sqrt(3.0) / 2, 1e-15);
  EXPECT_EQ(hertz_pressure(c, c.radius), 0.0);
  EXPECT_EQ(hertz_pressure(c, 2 * c.radius), 0.0);
  // The deepest shear at 0.48 a (§4.2, ν = 0.3): the one product, exact to its rounding.
  EXPECT_EQ(c.max_shear_depth, 0.48 * c.radius);
}
