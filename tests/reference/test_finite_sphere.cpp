// The finite-sphere reference (validation/reference/finite_sphere.hpp): its own convergence, its
// Hertz limit, and the impact quadrature against Hertz's closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "validation/reference/finite_sphere.hpp"

namespace ref = asperity::reference;

namespace {

const ref::FiniteSphereMaterial kUnit{.youngs_modulus = 1.0, .poisson_ratio = 0.3, .radius = 1.0};

double observed_order(double coarse, double middle, double fine) {
  return std::log2(std::abs((coarse - middle) / (middle - fine)));
}

}  // namespace

// The impact quadrature on Hertz's own law (g ≡ 1): peak (4/3) E* √R δ_m^{3/2} with
// ½ m v² = (8/15) E* √R δ_m^{5/2}, and duration 2 (2/5) B(2/5, 1/2) δ_m / v = 2.9432 δ_m / v
// (Johnson 1985, §11.4). The closed forms are exact; 1e-9 is the quadrature's round-off margin.
TEST(FiniteSphere, ImpactQuadratureReproducesHertz) {
  const ref::FiniteSphereLaw hertz{
      .poisson_ratio = 0.3, .coefficients = {1, 0, 0, 0, 0}, .s_max = 1.0};
  const double E = 10e6, R = 0.1, mass = 4.18879, v = 0.2;
  const ref::FiniteSphereImpact im = ref::impact_from_law(hertz, E, mass, R, v);
  const double Es = E / (1.0 - 0.09);
  const double dm = std::pow(0.5 * mass * v * v / (8.0 / 15.0 * Es * std::sqrt(R)), 0.4);
  EXPECT_NEAR(im.max_approach / dm, 1.0, 1e-12);
  EXPECT_NEAR(im.peak_force / (4.0 / 3.0 * Es * std::sqrt(R) * std::pow(dm, 1.5)), 1.0, 1e-12);
  EXPECT_NEAR(im.duration / (2.0 * 0.4 * std::beta(0.4, 0.5) * dm / v), 1.0, 1e-9);
  EXPECT_NEAR(im.duration * v / dm, 2.9432, 1e-4);  // Johnson's figure, to its 5 digits
}

// Refinement of the bipolar grid (M = 4, 8, 16 cells across). The revolved half-disc's volume
// converges to (4/3)πR³ (isoparametric Q9 edges on the circle: at least order 2, measured 4).
// F/F_Hertz at a fixed approach: the phase-averaged ratio converges at a measured order, and so
// does the oscillation that nodal contact leaves about it (the contact edge between two surface
// nodes: measured order 1.7–2.3, as h² for a nodal Signorini condition on a smooth gap).
TEST(FiniteSphere, ConvergesUnderRefinement) {
  std::vector<double> volume_error, g01, g107, osc01, osc107;
  for (int M : {4, 8, 16}) {
    const ref::FiniteSphere sphere(kUnit, {.angular_cells = M});
    volume_error.push_back(std::abs(sphere.volume() / (4.0 / 3.0 * std::numbers::pi) - 1.0));
    const auto r01 = sphere.averaged_force_ratio(0.01);
    const auto r107 = sphere.averaged_force_ratio(0.107);
    g01.push_back(r01.ratio);
    osc01.push_back(r01.oscillation);
    g107.push_back(r107.ratio);
    osc107.push_back(r107.oscillation);
  }
  EXPECT_GT(std::log2(volume_error[0] / volume_error[1]), 2.0);
  EXPECT_GT(std::log2(volume_error[1] / volume_error[2]), 2.0);
  EXPECT_LT(volume_error[2], 1e-5);
  for (const auto& [s, g, oscillation] :
       {std::tuple{0.01, g01, osc01}, std::tuple{0.107, g107, osc107}}) {
    const double p = observed_order(g[0], g[1], g[2]);
    const double richardson = (g[2] - g[1]) / (std::pow(2.0, p) - 1.0);
    std::printf(
        "a/R = %.3f: F/F_H %.7f %.7f %.7f, order %.2f, M = 16 off its limit by %.1e; "
        "oscillation %.1e %.1e %.1e\n",
        s, g[0], g[1], g[2], p, richardson, oscillation[0], oscillation[1], oscillation[2]);
    EXPECT_GT(p, 1.5);  // measured 1.9 and 3.3 on these levels
    // The M = 16 level (the default of finite_sphere_impact) is within 2e-4 of its limit: a
    // hundredth of the 2 % gate it serves.
    EXPECT_LT(std::abs(richardson), 2e-4);
    EXPECT_GT(std::log2(oscillation[0] / oscillation[1]), 1.5);
    EXPECT_GT(std::log2(oscillation[1] / oscillation[2]), 1.5);
  }
}

// The Hertz limit, for three Poisson ratios (E* = E/(1 − ν²) is the only way ν enters Hertz):
// the law's fitted c_0 (g at s → 0) is 1 within 2e-4, a third of the nodal oscillation it
// averages (±0.07 % at M = 16); at a/R = 0.005 the sphere is within 0.5 % of Hertz; the
// deviation grows as s (A + B ln s): between a/R = 0.005 and 0.02 its local exponent is
// 1 + B/(A + B ln s), measured 1.28 (ν = 0.2) to 1.02 (ν = 0.4), not 0 (a constant offset: the
// mesh) nor 2 (a curvature effect).
TEST(FiniteSphere, HertzLimitAndLinearDeviation) {
  for (double nu : {0.2, 0.3, 0.4}) {
    const ref::FiniteSphereMaterial material{
        .youngs_modulus = 1.0, .poisson_ratio = nu, .radius = 1.0};
    const ref::FiniteSphere sphere(material, {.angular_cells = 16});
    const ref::FiniteSphereLaw law = ref::fit_finite_sphere_law(sphere);
    const auto& c = law.coefficients;
    std::printf(
        "nu = %.1f: g = %.6f + %.4f s + %.4f s ln s + %.3f s^2 + %.3f s^3 (residual "
        "%.1e); (g-1)/s at a/R = 0.01: %.4f, 0.1: %.4f\n",
        nu, c[0], c[1], c[2], c[3], c[4], law.fit_residual, (ref::evaluate(law, 0.01) - 1) / 0.01,
        (ref::evaluate(law, 0.1) - 1) / 0.1);
    EXPECT_NEAR(c[0], 1.0, 2e-4);
    const double g005 = sphere.averaged_force_ratio(0.005).ratio;
    const double g02 = sphere.averaged_force_ratio(0.02).ratio;
    EXPECT_LT(std::abs(g005 - 1.0), 5e-3);
    EXPECT_GT(g005, 1.0);  // the finite sphere is stiffer than the half-space
    const double exponent = std::log((g02 - 1.0) / (g005 - 1.0)) / std::log(4.0);
    EXPECT_GT(exponent, 0.95);
    EXPECT_LT(exponent, 1.4);
  }
}

// The contact radius tends to Hertz's √(Rδ) as a/R → 0. a is interpolated between the last
// node in contact and the next (w^{2/3} linear in r outside the contact), whose spacing at
// M = 16 is 5 % of a: 1 % covers that interpolation.
TEST(FiniteSphere, ContactRadiusTendsToHertz) {
  const ref::FiniteSphere sphere(kUnit, {.angular_cells = 16});
  for (double s : {0.005, 0.01}) {
    const ref::FiniteSphereState st = sphere.at_approach(s * s);
    EXPECT_NEAR(st.contact_radius / s, 1.0, 0.01) << "a/R = " << s;
  }
}

// The impact the 3D gate calls (E = 10 MPa, ν = 0.3, ρ = 1000 kg/m³, R = 0.1 m): it tends to Hertz
// as the speed falls (a/R = 0.005: within 0.3 %, the law's own 0.36 % at that size raised to the
// power 2/5), its deviation from Hertz is the same from the M = 8 law as from the default M = 16
// within 0.02 % (the convergence of the impact itself).
TEST(FiniteSphere, ImpactTendsToHertzAndConverges) {
  const double E = 10e6, nu = 0.3, rho = 1000.0, R = 0.1;
  const double mass = 4.0 / 3.0 * std::numbers::pi * R * R * R * rho;
  const ref::FiniteSphereImpact slow = ref::finite_sphere_impact(E, nu, rho, R, 1e-4);
  EXPECT_NEAR(std::sqrt(slow.hertz_max_approach / R), 0.0052, 1e-4);
  EXPECT_NEAR(slow.peak_force / slow.hertz_peak_force, 1.0, 3e-3);
  EXPECT_NEAR(slow.duration / slow.hertz_duration, 1.0, 3e-3);

  const ref::FiniteSphereLaw law8 = ref::fit_finite_sphere_law(nu, {.angular_cells = 8});
  for (double v : {0.2, 0.465}) {
    const ref::FiniteSphereImpact im = ref::finite_sphere_impact(E, nu, rho, R, v);
    const ref::FiniteSphereImpact coarse = ref::impact_from_law(law8, E, mass, R, v);
    const double peak = im.peak_force / im.hertz_peak_force - 1.0;
    const double duration = im.duration / im.hertz_duration - 1.0;
    std::printf(
        "v = %.3f m/s, a/R = %.4f: peak %+.3f %%, duration %+.3f %% (M = 8: %+.3f %%, "
        "%+.3f %%)\n",
        v, std::sqrt(im.hertz_max_approach / R), 100 * peak, 100 * duration,
        100 * (coarse.peak_force / coarse.hertz_peak_force - 1.0),
        100 * (coarse.duration / coarse.hertz_duration - 1.0));
    EXPECT_NEAR(coarse.peak_force / coarse.hertz_peak_force - 1.0, peak, 2e-4);
    EXPECT_NEAR(coarse.duration / coarse.hertz_duration - 1.0, duration, 2e-4);
    EXPECT_GT(peak, 0.0);  // stiffer than Hertz: more force, shorter contact
    EXPECT_LT(duration, 0.0);
  }
  // The head-on pair at relative speed w is one sphere at w/2 on the plane of symmetry; its Hertz
  // values must then be Hertz's pair (E*_pair = E/(2(1 − ν²)), R* = R/2, m* = m/2, speed w).
  const double w = 0.4;
  const ref::FiniteSphereImpact pair = ref::finite_sphere_head_on(E, nu, rho, R, w);
  const double Es_pair = E / (2.0 * (1.0 - nu * nu)), R_pair = R / 2.0, m_pair = mass / 2.0;
  const double d_pair =
      std::pow(0.5 * m_pair * w * w / (8.0 / 15.0 * Es_pair * std::sqrt(R_pair)), 0.4);
  EXPECT_NEAR(
      pair.hertz_peak_force / (4.0 / 3.0 * Es_pair * std::sqrt(R_pair) * std::pow(d_pair, 1.5)),
      1.0, 1e-12);
  EXPECT_NEAR(pair.hertz_duration / (2.0 * 0.4 * std::beta(0.4, 0.5) * d_pair / w), 1.0, 1e-12);
  EXPECT_NEAR(2.0 * pair.hertz_max_approach / d_pair, 1.0, 1e-12);
}

// Bad arguments are programming errors of the caller (a test or a gate): named, thrown.
TEST(FiniteSphere, RefusesBadArguments) {
  EXPECT_THROW(ref::FiniteSphere({.youngs_modulus = 1.0, .poisson_ratio = 0.5, .radius = 1.0}, {}),
               std::invalid_argument);
  EXPECT_THROW(ref::FiniteSphere(kUnit, {.angular_cells = 1}), std::invalid_argument);
  EXPECT_THROW(ref::finite_sphere_impact(10e6, 0.3, 1000.0, 0.1, 0.0), std::invalid_argument);
  EXPECT_THROW(ref::finite_sphere_impact(-1.0, 0.3, 1000.0, 0.1, 0.2), std::invalid_argument);
  // A contact beyond the law's fitted range: a/R = 0.107 on a law fitted to 0.05.
  const ref::FiniteSphereLaw narrow{
      .poisson_ratio = 0.3, .coefficients = {1, 0, 0, 0, 0}, .s_max = 0.05};
  EXPECT_THROW(ref::impact_from_law(narrow, 10e6, 4.18879, 0.1, 0.2), std::invalid_argument);
}
