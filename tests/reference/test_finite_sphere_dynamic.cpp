// The dynamic finite-sphere reference (validation/reference/finite_sphere_dynamic.hpp): the
// scheme's conservation laws, its convergence in dt and in the mesh, its quasi-static limit as
// the impact slows, and Hertz at a tiny contact.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "validation/reference/finite_sphere.hpp"
#include "validation/reference/finite_sphere_dynamic.hpp"

namespace ref = asperity::reference;

namespace {

// The 3D gates' sphere (reports/fem/hertz_convergence.md): R = 0.1 m, E = 10 MPa, ν = 0.3,
// ρ = 1000 kg/m³.
constexpr double kE = 10e6, kNu = 0.3, kRho = 1000.0, kR = 0.1;
const double kMass = 4.0 / 3.0 * std::numbers::pi * kR * kR * kR * kRho;
const ref::FiniteSphereMaterial kMaterial{.youngs_modulus = kE, .poisson_ratio = kNu, .radius = kR};

// The speed whose Hertz contact radius is a/R (scenes/hertz_series.hpp, speed_for).
double speed_for(double a_over_R) {
  const double Es = kE / (1.0 - kNu * kNu);
  const double d = a_over_R * a_over_R * kR;
  return std::sqrt(16.0 * Es * std::sqrt(kR) * std::pow(d, 2.5) / (15.0 * kMass));
}

ref::FiniteSphereDynamicImpact run(double a_over_R, int M, double steps) {
  return ref::simulate_finite_sphere_impact(
      kMaterial, kMass, speed_for(a_over_R),
      {.mesh = {.angular_cells = M}, .steps_per_hertz_duration = steps});
}

double peak_error(const ref::FiniteSphereDynamicImpact& r) {
  return r.step_mean_peak_force / r.hertz_peak_force - 1.0;
}
double duration_error(const ref::FiniteSphereDynamicImpact& r) {
  return r.duration / r.hertz_duration - 1.0;
}

double observed_order(double coarse, double middle, double fine) {
  return std::log2(std::abs((coarse - middle) / (middle - fine)));
}

}  // namespace

// The scheme's two identities and what they leave. Newmark's average acceleration advances the
// momentum by the trapezoidal impulse of the contact force (Kᵀ annihilates the rigid
// translation), so ∫F dt = m (V_end − V_0) to round-off; and for linear M and K its energy
// changes by exactly the trapezoidal work of the contact forces, ½(f_n + f_{n+1})·Δu. That work
// is the scheme's only energy error: zero while a node stays in contact (its gap stays 0), nonzero
// only at the transitions (a node entering contact loses ½ R Δu, one leaving gains it). Measured
// +7.4e-4 of ½mv² here (+2e-5 to +7e-4 over the convergence table of reports/fem/
// finite_sphere_dynamic.md, +2.2e-3 at M = 8 with 2000 steps, where the contact chatters once):
// held below 2e-3. The rebound cannot carry more kinetic energy in its centre of mass than the
// sphere has in all (e² ≤ E_end/E_0), and an elastic rebound leaves a little in vibration: the
// impulse is 2mv within 1e-3 (the 3D runs: 0.9998).
TEST(FiniteSphereDynamic, ConservesMomentumAndEnergyToTheContactWork) {
  const ref::FiniteSphereDynamicImpact r = run(0.107, 8, 500);
  std::printf(
      "impulse / 2mv %.6f, rebound %.6f, energy end / start %.6f, contact work %.2e, "
      "largest excursion %.2e, contact intervals %d\n",
      r.impulse_ratio, r.rebound_ratio, r.energy_ratio, r.contact_work, r.energy_excursion,
      r.contact_intervals);
  EXPECT_NEAR(2.0 * r.impulse_ratio, 1.0 + r.rebound_ratio, 1e-9);
  EXPECT_NEAR(r.energy_ratio - 1.0, r.contact_work, 1e-9);
  EXPECT_LT(std::abs(r.contact_work), 2e-3);
  EXPECT_LT(r.energy_excursion, 2e-3);
  EXPECT_LE(r.rebound_ratio * r.rebound_ratio, r.energy_ratio);
  EXPECT_GT(r.impulse_ratio, 0.999);
  EXPECT_EQ(r.contact_intervals, 1);
}

// At a tiny contact both references are Hertz's impact: a/R = 0.005 on the coarse M = 8 mesh.
// Allowed: the finite sphere's own stiffening there (+0.18 % peak, −0.13 % duration, the
// quasi-static law) plus M = 8's single-state nodal oscillation (±0.26 % at a/R = 0.01,
// reports/fem/finite_sphere.md): 0.5 %. And the two references agree in duration within 0.05
// point there (measured 0.01), where the contact lasts 14 periods of the lowest mode.
TEST(FiniteSphereDynamic, TendsToHertzAtATinyContact) {
  const ref::FiniteSphereDynamicImpact r = run(0.005, 8, 500);
  const ref::FiniteSphereImpact q =
      ref::finite_sphere_impact_with_mass(kE, kNu, kMass, kR, speed_for(0.005));
  const double qs_duration = q.duration / q.hertz_duration - 1.0;
  std::printf(
      "a/R 0.005: dynamic peak %+.4f %%, duration %+.4f %%; quasi-static %+.4f %%, "
      "%+.4f %%\n",
      100 * peak_error(r), 100 * duration_error(r), 100 * (q.peak_force / q.hertz_peak_force - 1.0),
      100 * qs_duration);
  EXPECT_LT(std::abs(peak_error(r)), 0.005);
  EXPECT_LT(std::abs(duration_error(r)), 0.005);
  EXPECT_NEAR(duration_error(r), qs_duration, 5e-4);
  EXPECT_NEAR(r.hertz_peak_force, q.hertz_peak_force, 1e-12 * q.hertz_peak_force);
  EXPECT_NEAR(r.hertz_duration, q.hertz_duration, 1e-9 * q.hertz_duration);
}

TEST(FiniteSphereDynamic, RefusesBadArguments) {
  EXPECT_THROW(ref::finite_sphere_impact_dynamic(10e6, 0.3, 1000.0, 0.1, 0.0),
               std::invalid_argument);
  EXPECT_THROW(ref::finite_sphere_impact_dynamic(10e6, 0.5, 1000.0, 0.1, 0.2),
               std::invalid_argument);
  EXPECT_THROW(
      ref::simulate_finite_sphere_impact(kMaterial, kMass, 0.2, {.steps_per_hertz_duration = 10}),
      std::invalid_argument);
}

// Label `slow` from here on (tests/reference/CMakeLists.txt states the times).

// Convergence in the step on the default mesh (M = 16), dt = T_H/500, /1000, /2000 at a/R =
// 0.107. The step-mean peak (the force the scheme's momentum balance applies over a step) and
// the T/20-filtered peak converge at least at the scheme's second order (measured: +5.1160,
// +5.1038, +5.1038 %, order 9: the step error is below 1e-5 by T_H/1000); the duration within
// 1e-4 of the contact between the two finer steps (the least-squares end, measured 5.5e-5). The
// raw per-step peak does not converge (+6.7, +9.4, +28 %): end-of-step contact lets the contact
// nodes' velocities alternate from step to step (Carpenter, Taylor & Katona 1991), a period-2
// force the step mean cancels.
TEST(FiniteSphereDynamicSlow, ConvergesInTheStep) {
  std::vector<ref::FiniteSphereDynamicImpact> r;
  for (double steps : {500.0, 1000.0, 2000.0}) r.push_back(run(0.107, 16, steps));
  for (const auto& x : r)
    std::printf(
        "dt = T_H/%.0f: peak %+.4f %% (step mean %+.4f %%, filtered %+.4f %%), duration "
        "%+.4f %%, energy end / start − 1 %.1e\n",
        x.hertz_duration / x.dt, 100 * (x.peak_force / x.hertz_peak_force - 1.0),
        100 * peak_error(x), 100 * (x.filtered_peak_force / x.hertz_peak_force - 1.0),
        100 * duration_error(x), x.energy_ratio - 1.0);
  EXPECT_GT(observed_order(peak_error(r[0]), peak_error(r[1]), peak_error(r[2])), 2.0);
  auto filtered = [](const ref::FiniteSphereDynamicImpact& x) {
    return x.filtered_peak_force / x.hertz_peak_force - 1.0;
  };
  EXPECT_GT(observed_order(filtered(r[0]), filtered(r[1]), filtered(r[2])), 2.0);
  EXPECT_LT(std::abs(peak_error(r[2]) - peak_error(r[1])), 1e-4);
  EXPECT_LT(std::abs(duration_error(r[2]) - duration_error(r[1])), 1e-4);
  for (const auto& x : r) EXPECT_LT(std::abs(x.contact_work), 2e-3);
}

// As the impact slows the contact lasts more periods of the sphere's lowest axisymmetric mode
// (3.83 ms: T_c/T_mode = 10.2, 6.4, 4.3 at a/R = 0.02, 0.05, 0.107), and the dynamic reference
// tends to the quasi-static one. The duration difference falls with a/R at a measured order
// about 2 (1.7 between 0.02 and 0.05, 2.25 between 0.05 and 0.107): the inertia of the body
// (relative size (T_mode/T_c)² ∝ a/R) corrects only the finite body's share of the compliance,
// itself ∝ a/R, so the product goes as (a/R)² (the brief's ∝ a/R was the first factor alone).
// Asserted: a positive difference falling at every step with order in (1.3, 3). The peak's
// difference (−0.15 point at 0.107) is within M = 16's single-state nodal oscillation (±0.08 %,
// reports/fem/finite_sphere.md) below a/R = 0.05: asserted there within 0.1 point.
TEST(FiniteSphereDynamicSlow, TendsToTheQuasiStaticReferenceAsTheImpactSlows) {
  const std::vector<double> ar{0.02, 0.05, 0.107};
  std::vector<double> d_duration, d_peak;
  for (double a : ar) {
    const ref::FiniteSphereDynamicImpact r = run(a, 16, 500);
    const ref::FiniteSphereImpact q =
        ref::finite_sphere_impact_with_mass(kE, kNu, kMass, kR, speed_for(a));
    d_peak.push_back(peak_error(r) - (q.peak_force / q.hertz_peak_force - 1.0));
    d_duration.push_back(duration_error(r) - (q.duration / q.hertz_duration - 1.0));
    std::printf("a/R %.3f: dynamic − quasi-static: peak %+.4f, duration %+.4f point\n", a,
                100 * d_peak.back(), 100 * d_duration.back());
  }
  for (std::size_t i = 0; i < ar.size(); ++i) EXPECT_GT(d_duration[i], 0.0) << ar[i];
  for (std::size_t i = 1; i < ar.size(); ++i) {
    const double order = std::log(d_duration[i] / d_duration[i - 1]) / std::log(ar[i] / ar[i - 1]);
    std::printf("duration difference: order %.2f in a/R between %.3f and %.3f\n", order, ar[i - 1],
                ar[i]);
    EXPECT_GT(order, 1.3);
    EXPECT_LT(order, 3.0);
  }
  EXPECT_LT(std::abs(d_peak[0]), 1e-3);
  EXPECT_LT(std::abs(d_peak[1]), 1e-3);
}

// The gates' entry point: the default model (M = 16, T_H/1000), cached, with Hertz beside it;
// ρ given or the mass given are the same impact. At the 3D scene's a/R = 0.107 it differs from the
// quasi-static reference by more than 0.3 point in duration (measured +0.40), the criterion that
// moved the 3D gates onto it (tests/fdem/hertz_gate.hpp).
TEST(FiniteSphereDynamicSlow, GatesEntryPointIsTheDefaultModelCached) {
  const double v = speed_for(0.107);
  const ref::FiniteSphereDynamicImpact a = ref::finite_sphere_impact_dynamic(kE, kNu, kRho, kR, v);
  const ref::FiniteSphereDynamicImpact b =
      ref::finite_sphere_impact_dynamic_with_mass(kE, kNu, kMass, kR, v);
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.duration, b.duration);
  EXPECT_NEAR(a.dt * 1000.0, a.hertz_duration, 1e-12 * a.hertz_duration);
  const ref::FiniteSphereImpact q = ref::finite_sphere_impact(kE, kNu, kRho, kR, v);
  EXPECT_NEAR(a.hertz_peak_force, q.hertz_peak_force, 1e-12 * q.hertz_peak_force);
  EXPECT_GT(duration_error(a) - (q.duration / q.hertz_duration - 1.0), 0.003);
}

// Label `hertz-full` (outside CI: 45 s of CPU, most of it the M = 32 run). Convergence in the
// mesh at dt = T_H/1000, a/R = 0.107, M = 8, 16, 32 cells across: the step-mean peak at a
// measured order above 2 (measured +5.1987, +5.1038, +5.0892 %: order 2.71; 2.91 at T_H/2000),
// and the default M = 16 within 5e-4 of M = 32 in filtered peak and duration (measured 1.8e-4
// and 2.5e-4: the filtered peak's window is whole steps, the duration's end is the pole's
// release, neither converges monotonically at this level).
TEST(FiniteSphereDynamicFull, ConvergesInTheMesh) {
  std::vector<ref::FiniteSphereDynamicImpact> r;
  for (int M : {8, 16, 32}) r.push_back(run(0.107, M, 1000));
  for (const auto& x : r)
    std::printf("peak (step mean) %+.4f %%, filtered %+.4f %%, duration %+.4f %%\n",
                100 * peak_error(x), 100 * (x.filtered_peak_force / x.hertz_peak_force - 1.0),
                100 * duration_error(x));
  EXPECT_GT(observed_order(peak_error(r[0]), peak_error(r[1]), peak_error(r[2])), 2.0);
  EXPECT_NEAR(r[1].filtered_peak_force / r[1].hertz_peak_force,
              r[2].filtered_peak_force / r[2].hertz_peak_force, 5e-4);
  EXPECT_NEAR(duration_error(r[1]), duration_error(r[2]), 5e-4);
}
