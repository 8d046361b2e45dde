// Munjiza's potential contact kernel on single pairs of tetrahedra.
#include <gtest/gtest.h>

#include "solver/contact/munjiza_potential.hpp"

namespace asperity::contact {
namespace {

constexpr double kP = 1e8;  // Pa

TetNodes unit_tet(const Vec3& shift = Vec3::Zero(), double s = 1) {
  return {shift, shift + Vec3(s, 0, 0), shift + Vec3(0, s, 0), shift + Vec3(0, 0, s)};
}

TetNodes moved(TetNodes t, const Vec3& d) {
  for (Vec3& x : t) x += d;
  return t;
}

// A generic overlapping pair (no symmetry that could hide an error).
TetNodes target() {
  return {Vec3(0, 0, 0), Vec3(1.1, 0.1, -0.05), Vec3(0.2, 0.9, 0.1), Vec3(0.1, 0.15, 1.05)};
}
TetNodes contactor() {
  const Mat3 r = Eigen::AngleAxisd(0.4, Vec3(0.3, -1, 0.5).normalized()).toRotationMatrix();
  TetNodes t = {Vec3(0, 0, 0), Vec3(0.9, 0, 0), Vec3(0.1, 0.8, 0), Vec3(0.2, 0.1, 0.95)};
  for (Vec3& x : t) x = r * x + Vec3(0.15, 0.1, 0.2);
  return t;
}

TEST(MunjizaPotential, ApartGivesNothing) {
  const auto c = munjiza_potential(unit_tet(), unit_tet(Vec3(2, 0, 0)), kP, true);
  EXPECT_FALSE(c.touching());
  EXPECT_EQ(c.total_on_a().norm(), 0);
  EXPECT_EQ(c.energy, 0);
}

// Equal and opposite forces and no net moment (each traction acts at one point on both
// elements): to round-off, 1e-12 of the force scale.
TEST(MunjizaPotential, ForcesBalanceAndHaveNoNetMoment) {
  const TetNodes a = contactor(), b = target();
  const auto c = munjiza_potential(a, b, kP, false);
  ASSERT_TRUE(c.touching());
  Vec3 sum = Vec3::Zero(), moment = Vec3::Zero();
  double scale = 0;
  for (int i = 0; i < 4; ++i) {
    sum += c.on_a[i] + c.on_b[i];
    moment += a[i].cross(c.on_a[i]) + b[i].cross(c.on_b[i]);
    scale = std::max({scale, c.on_a[i].norm(), c.on_b[i].norm()});
  }
  ASSERT_GT(scale, 0);
  EXPECT_LT(sum.norm(), 1e-12 * scale);
  EXPECT_LT(moment.norm(), 1e-12 * scale);
}

// The force is the exact gradient of U = p ∫ (φ_a + φ_b) dV under a rigid translation of a
// (Munjiza 2004, eqs 2.20–2.23): central differences of U with step 1e-6 agree to O(h²) plus the
// non-smoothness of U where a vertex crosses a sub-tetrahedron face (U is C¹ there, so still
// O(h)); 1e-5 of |F| covers both.
TEST(MunjizaPotential, ForceIsMinusEnergyGradientUnderTranslation) {
  const TetNodes a = contactor(), b = target();
  const auto c = munjiza_potential(a, b, kP, true);
  ASSERT_GT(c.energy, 0);
  const Vec3 f = c.total_on_a();
  ASSERT_GT(f.norm(), 0);
  const double h = 1e-6;
  for (int k = 0; k < 3; ++k) {
    const Vec3 d = h * Vec3::Unit(k);
    const double up = munjiza_potential(moved(a, d), b, kP, true).energy;
    const double um = munjiza_potential(moved(a, -d), b, kP, true).energy;
    EXPECT_NEAR(f[k], -(up - um) / (2 * h), 1e-5 * f.norm()) << "axis " << k;
  }
}

// The same for a rotation of a about its centroid: the moment of the forces is minus dU/dθ
// (energy is conserved in rigid rotations too).
TEST(MunjizaPotential, MomentIsMinusEnergyGradientUnderRotation) {
  const TetNodes a = contactor(), b = target();
  const auto c = munjiza_potential(a, b, kP, true);
  ASSERT_TRUE(c.touching());
  const Vec3 centre = 0.25 * (a[0] + a[1] + a[2] + a[3]);
  Vec3 moment = Vec3::Zero();
  for (int i = 0; i < 4; ++i) moment += (a[i] - centre).cross(c.on_a[i]);
  const double h = 1e-6;
  for (int k = 0; k < 3; ++k) {
    auto rotated = [&](double angle) {
      const Mat3 r = Eigen::AngleAxisd(angle, Vec3::Unit(k)).toRotationMatrix();
      TetNodes t = a;
      for (Vec3& x : t) x = centre + r * (x - centre);
      return munjiza_potential(t, b, kP, true).energy;
    };
    EXPECT_NEAR(moment[k], -(rotated(h) - rotated(-h)) / (2 * h), 1e-5 * c.total_on_a().norm())
        << "axis " << k;
  }
}

// Analytic case: a small element wholly inside one sub-tetrahedron of a large one. Its own
// potential integrates to nothing over itself (φ_a = 0 on its faces), the target's gradient is
// the constant 4∇L_m there, so f_a = −p V_a 4∇L_m exactly, and U = p V_a (φ_b(centroid) + 1/4)
// (∫φ_a = V/4 for the centroid pyramid: each sub-tetrahedron holds a quarter of the volume and
// the mean of φ over it is 1/4).
TEST(MunjizaPotential, SmallElementInsideOneSubTetrahedron) {
  const TetNodes b = unit_tet(Vec3::Zero(), 1.0);
  // Near the face z = 0 (opposite node 3), inside that face's sub-tetrahedron.
  const double s = 0.02;
  const TetNodes a = unit_tet(Vec3(0.3, 0.3, 0.02), s);
  const auto c = munjiza_potential(a, b, kP, true);
  const double va = s * s * s / 6;
  // L₃ = z, so ∇(4 L₃) = (0, 0, 4): the force pushes a out through z = 0.
  const Vec3 expected(0, 0, -kP * va * 4);
  EXPECT_LT((c.total_on_a() - expected).norm(), 1e-9 * expected.norm());
  const Vec3 centroid = 0.25 * (a[0] + a[1] + a[2] + a[3]);
  EXPECT_NEAR(c.energy, kP * va * (4 * centroid.z() + 0.25), 1e-9 * c.energy);
  EXPECT_NEAR(c.depth, 0.02 + s, 1e-12);
}

}  // namespace
}  // namespace asperity::contact
