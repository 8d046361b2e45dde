// Conservation laws in sphere–sphere impacts: momentum to round-off, symmetric response.
#include <cmath>

#include <gtest/gtest.h>

#include "scenes/dem_scenes.hpp"
#include "solver/core/material.hpp"
#include "solver/dem/sphere_world.hpp"

using namespace asperity;

namespace {

// Two unequal spheres in an oblique, spinning, frictional, damped impact.
dem::SphereWorld oblique_pair() {
  dem::SphereWorld w;
  w.materials = {test::glass(0.4, 0.6)};
  w.law.normal = contact::NormalLaw::hertz;
  w.law.tangential = true;
  w.radius = {0.01, 0.015};
  for (double r : w.radius) {
    const double m = 2500 * 4.0 / 3.0 * M_PI * r * r * r;
    w.mass.push_back(m);
    w.inertia.push_back(0.4 * m * r * r);
  }
  w.material = {0, 0};
  w.body = {0, 1};
  w.fixed = {0, 0};
  w.x.resize(3, 2);
  w.v.resize(3, 2);
  w.w.resize(3, 2);
  w.x.col(0) = Vec3(0, 0.004, 0.0255);
  w.x.col(1) = Vec3(0, 0, 0);
  w.v.col(0) = Vec3(0.3, 0.2, -2.0);
  w.v.col(1) = Vec3(-0.1, 0, 0.5);
  w.w.col(0) = Vec3(10, -20, 5);
  w.w.col(1) = Vec3(0, 3, 0);
  dem::initialise(w);
  return w;
}

Vec3 momentum(const dem::SphereWorld& w) {
  return w.mass[0] * w.v.col(0) + w.mass[1] * w.v.col(1);
}
Vec3 angular_momentum(const dem::SphereWorld& w) {  // about the origin
  Vec3 l = Vec3::Zero();
  for (int i = 0; i < 2; ++i) {
    l += w.mass[i] * w.x.col(i).cross(Vec3(w.v.col(i))) + w.inertia[i] * w.w.col(i);
  }
  return l;
}

}  // namespace

TEST(Conservation, MomentumIsConservedToRoundOffInAnObliqueImpact) {
  dem::SphereWorld w = oblique_pair();
  const Vec3 p0 = momentum(w), l0 = angular_momentum(w);
  bool touched = false;
  for (int k = 0; k < 20000; ++k) {
    dem::step(w, 5e-8);
    touched = touched || w.contact_updates > 0;
  }
  ASSERT_TRUE(touched);
  // Equal and opposite contact forces: momentum changes only by round-off, ~1e-16 of |p| per
  // step, accumulated over 2e4 steps.
  EXPECT_LT((momentum(w) - p0).norm(), 1e-11 * p0.norm());
  // Torques are r × F about each centre with the contact point on the line of centres, so
  // angular momentum about any point is conserved as well (to the same round-off).
  EXPECT_LT((angular_momentum(w) - l0).norm(), 1e-10 * l0.norm());
}

TEST(Conservation, HeadOnImpactOfEqualSpheresIsMirrorSymmetric) {
  dem::SphereWorld w;
  w.materials = {test::glass(0.3, 0.7)};
  w.law.normal = contact::NormalLaw::hertz;
  w.radius = {0.01, 0.01};
  const double m = 2500 * 4.0 / 3.0 * M_PI * 1e-6;
  w.mass = {m, m};
  w.inertia = {0.4 * m * 1e-4, 0.4 * m * 1e-4};
  w.material = {0, 0};
  w.body = {0, 1};
  w.fixed = {0, 0};
  w.x.resize(3, 2);
  w.v.resize(3, 2);
  w.w = Eigen::Matrix3Xd::Zero(3, 2);
  w.x.col(0) = Vec3(-0.01001, 0, 0);
  w.x.col(1) = Vec3(0.01001, 0, 0);
  w.v.col(0) = Vec3(1, 0, 0);
  w.v.col(1) = Vec3(-1, 0, 0);
  dem::initialise(w);
  for (int k = 0; k < 20000; ++k) dem::step(w, 1e-8);
  // Mirror symmetry about x = 0 holds exactly in exact arithmetic; the two columns see the same
  // operations with opposite signs, so they agree to the last bits.
  EXPECT_NEAR(w.x(0, 0), -w.x(0, 1), 1e-15);
  EXPECT_NEAR(w.v(0, 0), -w.v(0, 1), 1e-12);
  // Damped: rebound speed e × 1 m/s (target 0.7; 1 % for the half-step dashpot lag).
  EXPECT_NEAR(-w.v(0, 0), 0.7, 0.007);
}
