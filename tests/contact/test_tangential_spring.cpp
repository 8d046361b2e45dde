// Incremental tangential spring with a Coulomb cap.
#include <gtest/gtest.h>

#include "solver/contact/tangential_spring.hpp"

using namespace asperity;
using namespace asperity::contact;

TEST(TangentialSpring, SticksElasticallyBelowTheCap) {
  const TangentialParams p{.stiffness = 1e6, .damping = 0, .friction = 0.5};
  const Vec3 v(1e-3, 0, 0);
  const TangentialForce f = tangential_spring(Vec3::Zero(), v, 1e-3, 100.0, p);
  // Hooke: F = −k u with u = v dt = 1e-6 m.
  EXPECT_DOUBLE_EQ(f.force.x(), -1.0);
  EXPECT_FALSE(f.sliding);
  // Conservation: no dissipation while sticking without a dashpot (round-off only).
  EXPECT_NEAR(f.dissipated, 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(f.energy, 0.5 * 1e6 * 1e-12);
}

TEST(TangentialSpring, SlidesAtMuTimesNormalForce) {
  const TangentialParams p{.stiffness = 1e6, .damping = 0, .friction = 0.3};
  const TangentialForce f = tangential_spring(Vec3::Zero(), Vec3(0, 2.0, 0), 1e-3, 10.0, p);
  EXPECT_TRUE(f.sliding);
  EXPECT_NEAR(f.force.norm(), 3.0, 1e-12);  // Coulomb: |F_t| = μ F_n
  EXPECT_NEAR(f.force.y(), -3.0, 1e-12);    // opposing the slip
  // Work balance over the step: the spring loads elastically to 3 N over u_e = 3/k, then slides
  // the remaining 2e-3 − u_e at 3 N; the work ½·3·u_e + 3·(2e-3 − u_e) is stored plus dissipated.
  const double ue = 3.0 / 1e6;
  EXPECT_NEAR(f.dissipated + f.energy, 0.5 * 3.0 * ue + 3.0 * (2e-3 - ue), 1e-12);
}
