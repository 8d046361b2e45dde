// The small-strain linear tetrahedron (fem/linear_elastic_tet.hpp): patch test, its distance from
// the neo-Hookean law (second order in the strain), forces as the energy's gradient, energy
// conservation of a free vibration within the central-difference bound, the batched loop, and the
// rotation guard (fires on a spinning body, not on a Hertz impact).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "scenes/fdem_scenes.hpp"
#include "solver/fdem/fdem_world.hpp"
#include "solver/fdem/structured_mesh.hpp"
#include "solver/fdem/time_step.hpp"
#include "solver/fem/linear_elastic_tet.hpp"
#include "solver/fem/tet_elements.hpp"
#include "solver/fem/tet_stress.hpp"
#include "tests/fem/energy_gradient_check.hpp"
#include "tests/fem/strained_ball.hpp"
#include "tests/fem/test_material.hpp"

namespace asperity::fem {
namespace {

using test_material::expect_forces_are_minus_energy_gradient;
using test_material::kE;
using test_material::kNu;
using test_material::kRho;

TetElements linear_elements(const TetMesh& m) {
  TetElements e = make_tet_elements(m.nodes, m.tets, kE, kNu, kRho, 0, "linear");
  e.law = ElasticLaw::linear;
  return e;
}

// Patch test: a uniform displacement gradient (strain and a small rotation) gives every element
// the same F, so the assembled force vanishes at the interior nodes, and the body as a whole is
// in balance with the uniform Hooke stress σ = λ tr ε I + 2 μ ε, ε = sym(F − I): Σ_a f_a = 0 and
// Σ_a f_a X_aᵀ = −σ V (each element gives −V₀ P Σ_a ∇N_a X_aᵀ = −V₀ P, the gradient of the
// identity map). Only round-off may remain: 1e-9 of the largest nodal force at the interior nodes
// (sums of ~20 terms), 1e-12 of σ for the virial.
TEST(LinearElasticTet, PatchTestUniformStrainIsReproduced) {
  const TetMesh m = fdem::box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), 3, 3, 3);
  const TetElements e = linear_elements(m);
  Mat3 F;
  F << 1.02, 0.01, -0.005, 0.003, 0.97, 0.02, -0.01, 0.004, 1.01;
  const Eigen::Matrix3Xd x = F * m.nodes;
  Eigen::Matrix3Xd f = Eigen::Matrix3Xd::Zero(3, x.cols());
  ASSERT_LT(add_internal_forces(e, x, x * 0, f, false).inverted, 0);
  const double scale = f.colwise().norm().maxCoeff();
  ASSERT_GT(scale, 0);
  std::vector<char> boundary(m.nodes.cols(), 0);
  for (Eigen::Index k = 0; k < m.surface.size(); ++k) boundary[m.surface.data()[k]] = 1;
  int interior = 0;
  Mat3 virial = Mat3::Zero();
  Vec3 total = Vec3::Zero();
  for (Eigen::Index i = 0; i < m.nodes.cols(); ++i) {
    total += f.col(i);
    virial += f.col(i) * m.nodes.col(i).transpose();
    if (boundary[i]) continue;
    ++interior;
    EXPECT_LT(f.col(i).norm(), 1e-9 * scale) << "node " << i;
  }
  EXPECT_EQ(interior, 8);
  const Mat3 eps = 0.5 * (F + F.transpose()) - Mat3::Identity();
  const Mat3 sigma = e.lame.lambda * eps.trace() * Mat3::Identity() + 2 * e.lame.mu * eps;
  EXPECT_LT(total.norm(), 1e-9 * scale);
  EXPECT_LT((virial + sigma).norm(), 1e-12 * sigma.norm()) << virial << "\n" << sigma;
}

// Nodal forces of one element under F = I + t G, by either law.
struct ElementForces {
  double f[4][3] = {};
  double energy = 0;
};
ElementForces forces_at(const TetReference& ref, const Mat3& F, ElasticLaw law) {
  const Vec3 X[4] = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  double x[4][3];
  for (int a = 0; a < 4; ++a) {
    const Vec3 p = F * X[a];
    for (int r = 0; r < 3; ++r) x[a][r] = p[r];
  }
  ElementForces out;
  const Lame l = lame_from(kE, kNu);
  double rotation = 0;
  if (law == ElasticLaw::linear) {
    linear_elastic_tet_forces<true>(ref.dm_inv.data(), ref.volume, l, x[0], x[1], x[2], x[3],
                                    out.f[0], out.f[1], out.f[2], out.f[3], &out.energy, &rotation);
  } else {
    neo_hookean_tet_forces<true>(ref.dm_inv.data(), ref.volume, l, x[0], x[1], x[2], x[3], out.f[0],
                                 out.f[1], out.f[2], out.f[3], &out.energy);
  }
  return out;
}

// The ParaView frames' measures of a linear-law element (fem/tet_stress.hpp): under uniaxial strain
// ε von Mises is 2 μ ε exactly (no O(ε) remainder, unlike neo-Hookean), and the energy density
// times V₀ is the force kernel's energy, to round-off (1e-12 relative).
TEST(LinearElasticTet, FrameStressIsHookesLawAndTheKernelsEnergy) {
  const Vec3 X[4] = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  const TetReference ref = tet_reference(X[0], X[1], X[2], X[3]);
  const Lame l = lame_from(kE, kNu);
  const double eps = 4e-3;
  Mat3 F = Mat3::Identity();
  F(0, 0) += eps;
  const TetStress st =
      tet_stress(ElasticLaw::linear, ref.dm_inv.data(), l, F * X[0], F * X[1], F * X[2], F * X[3]);
  EXPECT_NEAR(st.von_mises, 2 * l.mu * eps, 1e-12 * l.mu * eps);
  Mat3 G;
  G << 1.02, 0.01, -0.005, 0.003, 0.97, 0.02, -0.01, 0.004, 1.01;
  const TetStress sg =
      tet_stress(ElasticLaw::linear, ref.dm_inv.data(), l, G * X[0], G * X[1], G * X[2], G * X[3]);
  const ElementForces k = forces_at(ref, G, ElasticLaw::linear);
  EXPECT_NEAR(sg.energy_density * ref.volume, k.energy, 1e-12 * k.energy);
}

// Both laws have the same tangent at F = I, so their forces differ by O(t²) under F = I + t G:
// halving t divides the difference by 4. G has stretch, shear and a rotation part. The observed
// order over four halvings from t = 1e-2 must be 2 within 0.05 (the O(t³) remainder moves it by
// about t: 0.01 at the largest t; round-off is 1e-16 × E against differences ≥ 1e3 N).
TEST(LinearElasticTet, DiffersFromNeoHookeanAtSecondOrderInTheStrain) {
  const TetReference ref =
      tet_reference(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1));
  Mat3 G;
  G << 0.8, 0.3, -0.5, 0.1, -0.6, 0.4, -0.2, 0.7, 0.3;
  std::vector<double> diff;
  for (double t = 1e-2; t > 1e-3; t /= 2) {
    const Mat3 F = Mat3::Identity() + t * G;
    const ElementForces a = forces_at(ref, F, ElasticLaw::linear);
    const ElementForces b = forces_at(ref, F, ElasticLaw::neo_hookean);
    double d = 0;
    for (int n = 0; n < 4; ++n) {
      for (int r = 0; r < 3; ++r) d = std::max(d, std::abs(a.f[n][r] - b.f[n][r]));
    }
    diff.push_back(d);
  }
  ASSERT_EQ(diff.size(), 4u);
  for (std::size_t i = 0; i + 1 < diff.size(); ++i) {
    const double order = std::log2(diff[i] / diff[i + 1]);
    std::printf("t = %.5f: |f_linear − f_neo-Hookean| %.4e N, order %.4f\n", 1e-2 / std::pow(2, i),
                diff[i], order);
    EXPECT_NEAR(order, 2.0, 0.05) << "t = " << 1e-2 / std::pow(2, i) << ": " << diff[i];
  }
}

// The forces are minus the gradient of V₀Ψ = V₀ (λ/2 (tr ε)² + μ ε:ε): central differences at a
// finite strain, exact for a quadratic energy up to round-off (1e-6 of E with h = 1e-6 m on
// unit-size elements: the energy's round-off 1e-16 × 1e8 J over 2h).
TEST(LinearElasticTet, ForcesAreMinusEnergyGradient) {
  const TetReference ref =
      tet_reference(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1));
  const Lame l = lame_from(kE, kNu);
  expect_forces_are_minus_energy_gradient(
      [&](double(&x)[4][3], double(&f)[4][3]) {
        for (auto& row : f) row[0] = row[1] = row[2] = 0;
        double w = 0, rot = 0;
        linear_elastic_tet_forces<true>(ref.dm_inv.data(), ref.volume, l, x[0], x[1], x[2], x[3],
                                        f[0], f[1], f[2], f[3], &w, &rot);
        return w;
      },
      1e-6 * kE);
}

// The batched loop runs the linear law as the one-element kernel does, to round-off (the
// tolerances' reasons as for the neo-Hookean law: tests/fem/test_neo_hookean_tet.cpp), element by
// element on nodes of their own, inverted element included, and reports the largest rotation (to
// 1e-12 relative: the same few rounded operations) and its element.
TEST(TetElements, BatchedLinearLoopEqualsTheOneElementKernelToRoundOff) {
  const TetMesh m = fdem::ball_mesh(0.1, 3);  // 162 elements
  const TetElements ball = linear_elements(m);
  const test_material::Separated s =
      test_material::separated(ball, test_material::strained_ball(ball, m.nodes));
  Eigen::Matrix3Xd f = Eigen::Matrix3Xd::Zero(3, s.x.cols());
  const InternalForceResult r = add_internal_forces(s.e, s.x, s.x * 0, f, true);
  double energy = 0, largest = 0;
  int inverted = -1, rotated = -1;
  test_material::KernelAgreement forces;
  for (int k = 0; k < s.e.size(); ++k) {
    double g[4][3] = {};
    const double* x = s.x.data() + 12 * k;
    double rotation = 0;
    const double j = linear_elastic_tet_forces<true>(
        &s.e.dm_inv[9 * static_cast<std::size_t>(k)], s.e.volume[k], s.e.lame, x, x + 3, x + 6,
        x + 9, g[0], g[1], g[2], g[3], &energy, &rotation);
    if (!(j > 0) && inverted < 0) inverted = k;
    if (j > 0 && rotation > largest) largest = rotation, rotated = k;
    forces.add(s, f, k, g);
  }
  test_material::expect_batched_equals_kernel(r, energy, inverted, forces);
  EXPECT_LE(std::abs(r.max_rotation - largest), 1e-12 * largest);
  EXPECT_EQ(r.rotated, rotated);
  EXPECT_GT(largest, 0.0);
}

// A free body vibrating (an initial breathing velocity with a twist, no supports) under velocity
// Verlet, whose energy E = ½ vᵀMv + W(x) is conserved up to a bounded oscillation. The linear law
// makes the system exactly linear, so per mode the scheme conserves ½v² + ½ω²x²(1 − (ωdt)²/4)
// and E departs from it by at most (ωdt)²/4 / (1 − (ωdt)²/4) of it; the modes are M-orthogonal,
// so with ω ≤ ω_max (the element bound, rigorous) that is the bound on the whole body's relative
// energy error. Asserted: the bound at three steps, and the error falling at order 2 (within
// 0.15: the excited modes' mix shifts slightly with dt) as the step halves. No drift.
TEST(LinearElasticTet, FreeVibrationConservesEnergyWithinTheSchemesBound) {
  const TetMesh m = fdem::ball_mesh(0.1, 4);
  const TetElements e = linear_elements(m);
  std::vector<double> mass(static_cast<std::size_t>(m.nodes.cols()), 0.0);
  add_lumped_mass(e, mass);
  const double omega = element_critical_step(e).omega_max;
  const Vec3 centre = m.nodes.rowwise().mean();
  Eigen::Matrix3Xd v0(3, m.nodes.cols());
  for (Eigen::Index i = 0; i < m.nodes.cols(); ++i) {
    const Vec3 r = m.nodes.col(i) - centre;
    // Breathing plus a shear in the xy-plane (a symmetric velocity gradient: no rigid spin), m/s.
    v0.col(i) = 0.5 * r / 0.1 + 0.3 * Vec3(r.y(), r.x(), 0) / 0.1;
  }
  auto energy_of = [&](const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, Eigen::Matrix3Xd& f) {
    f.setZero();
    const double w = add_internal_forces(e, x, v * 0, f, true).energy;
    double k = 0;
    for (Eigen::Index i = 0; i < v.cols(); ++i) k += 0.5 * mass[i] * v.col(i).squaredNorm();
    return k + w;
  };
  // The same time for every step: 400 × 2/ω_max, several periods of the slowest modes.
  const double t_end = 400 * 2.0 / omega;
  std::vector<double> error;
  for (const double fraction : {0.4, 0.2, 0.1}) {
    const double dt = fraction * 2.0 / omega;
    Eigen::Matrix3Xd x = m.nodes, v = v0, f(3, x.cols());
    const double e0 = energy_of(x, v, f);
    double worst = 0;
    const long n = std::lround(t_end / dt);
    for (long s = 0; s < n; ++s) {
      for (Eigen::Index i = 0; i < x.cols(); ++i) v.col(i) += 0.5 * dt * f.col(i) / mass[i];
      x += dt * v;
      f.setZero();
      add_internal_forces(e, x, v * 0, f, false);
      for (Eigen::Index i = 0; i < x.cols(); ++i) v.col(i) += 0.5 * dt * f.col(i) / mass[i];
      if (s % 10 == 9) worst = std::max(worst, std::abs(energy_of(x, v, f) / e0 - 1));
    }
    const double wdt2 = std::pow(omega * dt, 2) / 4;
    std::printf("dt = %.2f × 2/ω_max: largest |E/E0 − 1| %.3e, bound %.3e\n", fraction, worst,
                wdt2 / (1 - wdt2));
    EXPECT_LT(worst, wdt2 / (1 - wdt2)) << "dt = " << fraction << " × 2/ω_max";
    error.push_back(worst);
  }
  for (std::size_t i = 0; i + 1 < error.size(); ++i) {
    std::printf("order %.3f\n", std::log2(error[i] / error[i + 1]));
    EXPECT_NEAR(std::log2(error[i] / error[i + 1]), 2.0, 0.15) << error[i] << " " << error[i + 1];
  }
}

// A deformable body spinning at Ω about z: its elements rotate by Ω t, and the linear law's world
// stops (failure: exit 3 in a run) once sin θ passes kLinearMaxRotation, near t = asin(bound)/Ω
// (within 10 %: the linear law's spurious stress deforms the spinning body a little); the same body
// neo-Hookean spins on.
TEST(LinearElasticTet, RotationGuardStopsASpinningBody) {
  const double spin = 50;  // rad/s
  for (const ElasticLaw law : {ElasticLaw::linear, ElasticLaw::neo_hookean}) {
    fdem::WorldDef def;
    Material mat = fdem::scenes::rubbery();
    mat.law = law;
    def.bodies.push_back({.name = "spinner",
                          .kind = fdem::BodyKind::deformable,
                          .mesh = fdem::ball_mesh(0.1, 3),
                          .material = mat,
                          .angular_velocity = Vec3(0, 0, spin)});
    fdem::World w = fdem::make_world(def);
    const double dt = 0.5 * fdem::critical_step(w).critical;
    const double t_guard = std::asin(kLinearMaxRotation) / spin;
    while (w.time < 2 * t_guard && w.failure.empty()) fdem::step(w, dt);
    if (law == ElasticLaw::linear) {
      ASSERT_FALSE(w.failure.empty());
      EXPECT_NE(w.failure.find("rotated by"), std::string::npos) << w.failure;
      EXPECT_NE(w.failure.find("not frame-indifferent"), std::string::npos) << w.failure;
      EXPECT_NEAR(w.time, t_guard, 0.1 * t_guard) << w.failure;
    } else {
      EXPECT_TRUE(w.failure.empty()) << w.failure;
      EXPECT_EQ(w.max_rotation, 0.0);
    }
  }
}

// The Hertz impact the linear law is for (a ball on a block at a/R ≈ 0.15, the largest contact of
// the Hertz sequences) turns the surface at the contact's edge by about a/R (its slope there), and
// its elements by less, inside the guard: the impact runs to the end. The structured ball (6
// cells per cube side) keeps this a unit test; the graded Hertz levels' own largest rotations are
// in reports/fem/hertz_convergence.md (bench_hertz's max_rotation).
TEST(LinearElasticTet, RotationGuardLetsAHertzImpactRun) {
  Material mat = fdem::scenes::rubbery();
  mat.law = ElasticLaw::linear;
  // v ∝ (a/R)^{5/2}: 0.2 m/s gives a/R = 0.107 (scenes/hertz_spheres.hpp), 0.46 gives 0.15.
  fdem::World w = fdem::make_world(
      fdem::scenes::ball_on_block(0.1, 6, 0.46, fdem::BodyKind::deformable, mat, 2e-4));
  const fdem::scenes::Impact impact = fdem::scenes::run_impact(w, 0.1);
  EXPECT_TRUE(w.failure.empty()) << w.failure;
  EXPECT_GT(impact.peak_force, 0);
  EXPECT_GT(w.max_rotation, 0.0);
  EXPECT_LT(w.max_rotation, kLinearMaxRotation);
  std::printf("Hertz impact at a/R 0.15, linear law: largest element rotation %.4f (guard %.2f)\n",
              w.max_rotation, kLinearMaxRotation);
}

}  // namespace
}  // namespace asperity::fem
