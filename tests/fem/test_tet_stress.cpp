// The element stress measures behind the ParaView frames (fem/tet_stress.hpp): the linear limit,
// shear, and the energy density against the force kernel's own energy.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/fem/neo_hookean_tet.hpp"
#include "solver/fem/tet_stress.hpp"
#include "tests/fem/test_material.hpp"

namespace asperity::fem {
namespace {

using test_material::kE;
using test_material::kNu;

// A reference tetrahedron and its Dm⁻¹ (column-major, as TetElements stores it).
struct Reference {
  Vec3 x[4] = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  TetReference ref = tet_reference(x[0], x[1], x[2], x[3]);
};

TetStress stress_under(const Mat3& f) {
  const Reference r;
  return neo_hookean_tet_stress(r.ref.dm_inv.data(), lame_from(kE, kNu), f * r.x[0], f * r.x[1],
                                f * r.x[2], f * r.x[3]);
}

// Uniaxial strain ε along x: linear elasticity gives σxx = (λ + 2μ) ε, σyy = σzz = λ ε, so von
// Mises |σxx − σyy| = 2 μ ε. The neo-Hookean tangent at F = I is exactly that law, so the
// relative error is O(ε): it must halve when ε halves (observed order 1 ± 0.05), and be below
// 2 ε at ε = 1e-3.
TEST(TetStress, UniaxialStrainVonMisesConvergesToLinearElasticity) {
  const Lame l = lame_from(kE, kNu);
  double err_prev = 0;
  for (const double eps : {4e-3, 2e-3, 1e-3}) {
    Mat3 f = Mat3::Identity();
    f(0, 0) += eps;
    const double err = std::abs(stress_under(f).von_mises - 2 * l.mu * eps) / (2 * l.mu * eps);
    if (err_prev > 0) {
      EXPECT_NEAR(std::log2(err_prev / err), 1.0, 0.05);
    }
    err_prev = err;
  }
  EXPECT_LT(err_prev, 2e-3);
}

// Simple shear γ: σxy = μ γ in the linear limit and von Mises √3 μ γ; the neo-Hookean shear
// stress is exactly μ γ at any γ (Bonet & Wood 2008, §6.4.3) and the normal stresses μγ² are
// second order, so at γ = 1e-4 the relative error is O(γ) < 1e-3.
TEST(TetStress, SimpleShearVonMises) {
  const double gamma = 1e-4, mu = lame_from(kE, kNu).mu;
  Mat3 f = Mat3::Identity();
  f(0, 1) = gamma;
  EXPECT_NEAR(stress_under(f).von_mises, std::sqrt(3.0) * mu * gamma, 1e-3 * mu * gamma);
}

// A rigid rotation carries no stress: von Mises and energy 0 to round-off (1e-9 of μ × 1e-6).
TEST(TetStress, RigidRotationIsStressFree) {
  const Mat3 r = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const TetStress s = stress_under(r);
  EXPECT_LT(s.von_mises, 1e-6 * lame_from(kE, kNu).mu);
  EXPECT_LT(std::abs(s.energy_density), 1e-6 * lame_from(kE, kNu).mu);
}

// The energy density times V₀ is the energy the force kernel integrates (the same Ψ, eq. 6.27):
// equal to round-off (1e-12 relative) under a general finite deformation.
TEST(TetStress, EnergyDensityMatchesForceKernel) {
  const Reference r;
  Mat3 f;
  f << 1.05, 0.02, -0.01, 0.03, 0.96, 0.04, -0.02, 0.01, 1.08;
  Vec3 x[4], g[4];
  for (int i = 0; i < 4; ++i) x[i] = f * r.x[i], g[i].setZero();
  double energy = 0;
  neo_hookean_tet_forces<true>(r.ref.dm_inv.data(), r.ref.volume, lame_from(kE, kNu), x[0].data(),
                               x[1].data(), x[2].data(), x[3].data(), g[0].data(), g[1].data(),
                               g[2].data(), g[3].data(), &energy);
  const TetStress s = stress_under(f);
  EXPECT_NEAR(s.energy_density * r.ref.volume, energy, 1e-12 * std::abs(energy));
  EXPECT_NEAR(s.j, f.determinant(), 1e-14);
}

}  // namespace
}  // namespace asperity::fem
