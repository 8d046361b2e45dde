// The potential contact's Coulomb friction (contact/potential_friction.hpp) on one pair of
// tetrahedra, no world: its stiffness is the secant normal stiffness |F_n| / depth, its force is
// capped at μ |F_n|, and the barycentric distribution hands each element the whole force.
#include <array>
#include <cmath>

#include <gtest/gtest.h>

#include "solver/contact/potential_friction.hpp"

using namespace asperity;

namespace {

const contact::TetNodes kA{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
const contact::TetNodes kB{Vec3(0.1, 0.1, -0.8), Vec3(0.9, 0.1, -0.8), Vec3(0.1, 0.9, -0.8),
                           Vec3(0.1, 0.1, 0.5)};
const Vec3 kPoint(0.2, 0.2, 0.1);      // inside both
const Vec3 kNormalForce(0, 0, 100.0);  // N, on a
const double kDepth = 1e-3;            // m: the secant stiffness is 1e5 N/m

std::array<Vec3, 4> each_node(const Vec3& v) {
  return {v, v, v, v};
}

Vec3 sum(const std::array<Vec3, 4>& f) {
  return f[0] + f[1] + f[2] + f[3];
}

}  // namespace

// Sticking: a tangential slip velocity v for dt gives the spring −k_t v dt with k_t = |F_n| /
// depth, and the normal part of the relative velocity none; each element's nodal forces sum to it
// (barycentric coordinates sum to 1: a few units of round-off, 1e-14 of the force).
TEST(PotentialFriction, StickingSpringIsTheSecantStiffnessTimesTheSlip) {
  const Vec3 v(0.01, 0, -0.5);  // a's velocity; its normal part must not count
  const double dt = 1e-6;
  const contact::PotentialFriction f =
      contact::potential_friction(kA, kB, each_node(v), each_node(Vec3::Zero()), kPoint,
                                  kNormalForce, kDepth, Vec3::Zero(), dt, 0.5);
  const Vec3 expected(-1e5 * 0.01 * dt, 0, 0);
  EXPECT_FALSE(f.tangential.sliding);
  EXPECT_NEAR((f.tangential.force - expected).norm(), 0, 1e-14 * expected.norm());
  EXPECT_NEAR((sum(f.on_a) - f.tangential.force).norm(), 0, 1e-14 * expected.norm());
  EXPECT_NEAR((sum(f.on_b) - f.tangential.force).norm(), 0, 1e-14 * expected.norm());
  // Stored energy |F|²/(2 k_t).
  EXPECT_NEAR(f.tangential.energy, expected.squaredNorm() / 2e5, 1e-12 * f.tangential.energy);
}

// Sliding: the force is μ |F_n| along the trial, whatever the slip.
TEST(PotentialFriction, SlidingForceIsCappedAtMuTimesTheNormalForce) {
  const contact::PotentialFriction f =
      contact::potential_friction(kA, kB, each_node(Vec3(0, 3, 0)), each_node(Vec3::Zero()), kPoint,
                                  kNormalForce, kDepth, Vec3::Zero(), 1e-3, 0.3);
  EXPECT_TRUE(f.tangential.sliding);
  EXPECT_NEAR(f.tangential.force.norm(), 0.3 * 100.0, 1e-12);
  EXPECT_LT(f.tangential.force.y(), 0);  // against a's slip
}

// Equal velocities: no slip, no force, up to the round-off of the two barycentric sums (each
// within 1e-14 of the nodes' velocity): below 1e-14 of the spring a slip of |v| for dt would load.
TEST(PotentialFriction, NoRelativeMotionNoForce) {
  const Vec3 v(0.3, -0.2, -1);
  const contact::PotentialFriction f = contact::potential_friction(
      kA, kB, each_node(v), each_node(v), kPoint, kNormalForce, kDepth, Vec3::Zero(), 1e-4, 0.5);
  EXPECT_LT(f.tangential.force.norm(), 1e-14 * (100.0 / kDepth) * 1e-4 * v.norm());
}
