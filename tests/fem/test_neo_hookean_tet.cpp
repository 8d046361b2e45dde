// The neo-Hookean tetrahedron: patch test, linear limit, energy–force consistency, time step.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Eigenvalues>

#include "solver/fdem/structured_mesh.hpp"
#include "solver/fem/neo_hookean_tet.hpp"
#include "solver/fem/tet_elements.hpp"
#include "tests/fem/energy_gradient_check.hpp"
#include "tests/fem/strained_ball.hpp"
#include "tests/fem/test_material.hpp"

namespace asperity::fem {
namespace {

using test_material::expect_forces_are_minus_energy_gradient;
using test_material::kE;
using test_material::kNu;
using test_material::kRho;

// Σ internal forces of a mesh deformed by x = F X (+ c); the interior nodes must carry zero force.
Eigen::Matrix3Xd forces_under(const TetMesh& m, const Mat3& F, const TetElements& e) {
  Eigen::Matrix3Xd x = F * m.nodes;
  Eigen::Matrix3Xd f = Eigen::Matrix3Xd::Zero(3, x.cols());
  const Eigen::Matrix3Xd v = Eigen::Matrix3Xd::Zero(3, x.cols());
  EXPECT_LT(add_internal_forces(e, x, v, f, false).inverted, 0);
  return f;
}

// Patch test: under a uniform deformation every element has the same F, so the assembled
// internal force vanishes at interior nodes and equals the traction P·N dA at the boundary.
// Only round-off may remain: 1e-9 of the largest nodal force (forces are sums of ~20 terms).
TEST(NeoHookeanTet, PatchTestUniformStrainIsReproduced) {
  const TetMesh m = fdem::box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), 3, 3, 3);
  const TetElements e = make_tet_elements(m.nodes, m.tets, kE, kNu, kRho, 0, "patch");
  Mat3 F;
  F << 1.02, 0.01, -0.005, 0.003, 0.97, 0.02, -0.01, 0.004, 1.01;
  const Eigen::Matrix3Xd f = forces_under(m, F, e);
  const double scale = f.colwise().norm().maxCoeff();
  ASSERT_GT(scale, 0);
  std::vector<char> boundary(m.nodes.cols(), 0);
  for (Eigen::Index k = 0; k < m.surface.size(); ++k) boundary[m.surface.data()[k]] = 1;
  int interior = 0;
  for (Eigen::Index i = 0; i < m.nodes.cols(); ++i) {
    if (boundary[i]) continue;
    ++interior;
    EXPECT_LT(f.col(i).norm(), 1e-9 * scale) << "node " << i;
  }
  EXPECT_EQ(interior, 8);
  // Each element's F equals the imposed one exactly: check on element 0.
  const Vec3 x0 = F * m.nodes.col(m.tets(0, 0));
  Mat3 ds;
  ds << F * m.nodes.col(m.tets(1, 0)) - x0, F * m.nodes.col(m.tets(2, 0)) - x0,
      F * m.nodes.col(m.tets(3, 0)) - x0;
  EXPECT_LT((ds * Eigen::Map<const Mat3>(e.dm_inv.data()) - F).norm(), 1e-14);
}

// Rigid rotation: zero force and zero energy (objectivity), to round-off.
TEST(NeoHookeanTet, RigidRotationIsStressFree) {
  const TetMesh m = fdem::box_mesh(Vec3(0, 0, 0), Vec3(1, 2, 1), 2, 2, 2);
  const TetElements e = make_tet_elements(m.nodes, m.tets, kE, kNu, kRho, 0, "rot");
  const Mat3 r = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3Xd x = r * m.nodes;
  Eigen::Matrix3Xd f = Eigen::Matrix3Xd::Zero(3, x.cols());
  const auto res = add_internal_forces(e, x, x * 0, f, true);
  // Forces scale: E × area ≈ 1e9 N; round-off of a rotation ≈ 1e-15 relative.
  EXPECT_LT(f.norm(), 1e-5);
  EXPECT_LT(std::abs(res.energy), 1e-6);
}

// Small strain: the neo-Hookean stress equals Hooke's law with λ, μ from E, ν to second order in
// the strain (1e-6 strain: relative difference ~1e-6).
TEST(NeoHookeanTet, SmallStrainIsLinearElasticity) {
  const TetMesh m = fdem::box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), 1, 1, 1);
  const TetElements e = make_tet_elements(m.nodes, m.tets, kE, kNu, kRho, 0, "lin");
  const double eps = 1e-6;
  Mat3 F = Mat3::Identity();
  F(0, 0) += eps;
  const Eigen::Matrix3Xd f = forces_under(m, F, e);
  // Uniaxial strain: σ_xx = (λ + 2μ) ε on the face x = 1 (area 1): Σ f_x over its nodes.
  const Lame l = lame_from(kE, kNu);
  double fx = 0;
  for (Eigen::Index i = 0; i < m.nodes.cols(); ++i) {
    if (m.nodes(0, i) == 1.0) fx += f(0, i);
  }
  // Internal forces are −∂W/∂x: the face's nodes are pulled back by σ_xx · A.
  EXPECT_NEAR(-fx, (l.lambda + 2 * l.mu) * eps, 1e-5 * (l.lambda + 2 * l.mu) * eps);
}

// Forces are minus the energy gradient: central differences of V₀Ψ at a finite strain, to the
// truncation error O(h²) ≈ 1e-7 relative with h = 1e-6 m on unit-size elements.
TEST(NeoHookeanTet, ForcesAreMinusEnergyGradient) {
  const TetReference ref =
      tet_reference(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1));
  const Lame l = lame_from(kE, kNu);
  expect_forces_are_minus_energy_gradient(
      [&](double(&x)[4][3], double(&f)[4][3]) {
        for (auto& row : f) row[0] = row[1] = row[2] = 0;
        double w = 0;
        neo_hookean_tet_forces<true>(ref.dm_inv.data(), ref.volume, l, x[0], x[1], x[2], x[3], f[0],
                                     f[1], f[2], f[3], &w);
        return w;
      },
      1e-6 * kE);
}

// The batched element loop (add_internal_forces) is the one-element kernel run element by
// element, only scheduled differently, and in a target clone with FMA its multiply-adds fused
// (fem/internal_forces.cpp): element by element (each on nodes of its own, so that a node's force
// is one element's), the same forces to 1e-12 of the element's unit-strain force. Why 1e-12:
// a component is about twenty rounded operations on terms at most a few unit-strain forces
// (strains here up to ~0.3), and fusing or reordering moves each by an ulp, ~1e-15 of the scale;
// a wrong term or index moves it by the strain itself, ≥ 1e-3. The energy (a sum of Ψ ≥ 0 in the
// same order) to 1e-12 relative. On a mesh whose element count is no multiple of the batch, with
// one element inverted (reported, adding nothing, in both).
TEST(TetElements, BatchedLoopEqualsTheOneElementKernelToRoundOff) {
  const TetMesh m = fdem::ball_mesh(0.1, 3);  // 162 elements
  const TetElements ball = make_tet_elements(m.nodes, m.tets, kE, kNu, kRho, 0, "ball");
  const test_material::Separated s =
      test_material::separated(ball, test_material::strained_ball(ball, m.nodes));
  Eigen::Matrix3Xd f = Eigen::Matrix3Xd::Zero(3, s.x.cols());
  const InternalForceResult r = add_internal_forces(s.e, s.x, s.x * 0, f, true);
  double energy = 0;
  int inverted = -1;
  test_material::KernelAgreement forces;
  for (int k = 0; k < s.e.size(); ++k) {
    double g[4][3] = {};
    const double* x = s.x.data() + 12 * k;
    const double j = neo_hookean_tet_forces<true>(&s.e.dm_inv[9 * static_cast<std::size_t>(k)],
                                                  s.e.volume[k], s.e.lame, x, x + 3, x + 6, x + 9,
                                                  g[0], g[1], g[2], g[3], &energy);
    if (!(j > 0) && inverted < 0) inverted = k;
    forces.add(s, f, k, g);
  }
  test_material::expect_batched_equals_kernel(r, energy, inverted, forces);
}

// An inverted element is reported, not hidden, and adds no force.
TEST(NeoHookeanTet, InvertedElementIsReported) {
  const TetMesh m = fdem::box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), 1, 1, 1);
  const TetElements e = make_tet_elements(m.nodes, m.tets, kE, kNu, kRho, 0, "inv");
  Eigen::Matrix3Xd x = m.nodes;
  x.col(m.tets(3, 2)) = x.col(m.tets(0, 2)) - (x.col(m.tets(3, 2)) - x.col(m.tets(0, 2)));
  Eigen::Matrix3Xd f = Eigen::Matrix3Xd::Zero(3, x.cols());
  const auto r = add_internal_forces(e, x, x * 0, f, false);
  EXPECT_GE(r.inverted, 0);
  EXPECT_LE(r.inverted_j, 0);
}

// The element critical step is conservative for the assembled mesh: the global largest
// eigenvalue of M⁻¹K (dense solve on a small mesh) is below the element bound, and not
// far below it (a useless bound would also pass the first check: within a factor 2 in ω).
TEST(TetElements, ElementStepBoundsTheGlobalOne) {
  const TetMesh m = fdem::ball_mesh(1.0, 2);
  const TetElements e = make_tet_elements(m.nodes, m.tets, kE, kNu, kRho, 0, "ball");
  const int n = static_cast<int>(m.nodes.cols());
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  std::vector<double> mass(n, 0.0);
  add_lumped_mass(e, mass);
  for (int t = 0; t < e.size(); ++t) {
    const TetReference r{.dm_inv = Eigen::Map<const Mat3>(&e.dm_inv[9 * t]), .volume = e.volume[t]};
    const auto ke = tet_stiffness(r, e.lame);
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) {
        k.block<3, 3>(3 * e.tets(a, t), 3 * e.tets(b, t)) += ke.block<3, 3>(3 * a, 3 * b);
      }
    }
  }
  Eigen::VectorXd s(3 * n);
  for (int i = 0; i < 3 * n; ++i) s[i] = 1.0 / std::sqrt(mass[i / 3]);
  const Eigen::MatrixXd a = s.asDiagonal() * k * s.asDiagonal();
  const double omega_global =
      std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a).eigenvalues().maxCoeff());
  const ElementStep es = element_critical_step(e);
  EXPECT_LE(omega_global, es.omega_max * (1 + 1e-12));
  EXPECT_GT(omega_global, 0.5 * es.omega_max);
}

}  // namespace
}  // namespace asperity::fem
