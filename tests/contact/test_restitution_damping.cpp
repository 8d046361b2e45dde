// The e → ζ map: exact inverse, checked against the closed form where one exists.
#include <cmath>

#include <gtest/gtest.h>

#include "solver/contact/restitution_damping.hpp"

using namespace asperity::contact;

TEST(RestitutionDamping, ElasticIsUndamped) {
  EXPECT_EQ(damping_for_restitution(NormalLaw::hertz, 1.0), 0.0);
  // RK4 with h = 2e-4 on the undamped contact returns e = 1 to ~1e-9.
  EXPECT_NEAR(restitution_for_damping(NormalLaw::hertz, 0.0), 1.0, 1e-8);
  EXPECT_NEAR(restitution_for_damping(NormalLaw::linear, 0.0), 1.0, 1e-8);
}

TEST(RestitutionDamping, MapInvertsItself) {
  for (NormalLaw law : {NormalLaw::linear, NormalLaw::hertz}) {
    for (double e : {0.1, 0.3, 0.5, 0.7, 0.9}) {
      const double zeta = damping_for_restitution(law, e);
      // Bisection stops at 1e-12 relative in ζ; e(ζ) is smooth, so e is met to ~1e-10.
      EXPECT_NEAR(restitution_for_damping(law, zeta), e, 1e-8) << "e = " << e;
    }
  }
}

TEST(RestitutionDamping, LinearWithoutClippingMatchesTheClosedForm) {
  // While ζ is small the clipped tail is tiny; the unclipped closed form
  // e = exp(−πξ/√(1−ξ²)) must then agree. The clipped law separates slightly later and with a
  // slightly higher speed, so the numerical e is above the closed form and close to it.
  for (double zeta : {0.01, 0.05, 0.1}) {
    const double numeric = restitution_for_damping(NormalLaw::linear, zeta);
    const double closed = linear_unclipped_restitution(zeta);
    EXPECT_GE(numeric, closed - 1e-9);
    EXPECT_NEAR(numeric, closed, 2 * zeta * zeta) << "zeta = " << zeta;  // clipping effect O(ζ²)
  }
}

TEST(RestitutionDamping, RestitutionFallsMonotonicallyWithDamping) {
  double last = 1.0;
  for (double zeta = 0.1; zeta < 3; zeta += 0.3) {
    const double e = restitution_for_damping(NormalLaw::hertz, zeta);
    EXPECT_LT(e, last);
    last = e;
  }
}

TEST(RestitutionDamping, RejectsRestitutionOutsideTheUnitInterval) {
  EXPECT_THROW(damping_for_restitution(NormalLaw::hertz, 0.0), std::invalid_argument);
  EXPECT_THROW(damping_for_restitution(NormalLaw::hertz, 1.2), std::invalid_argument);
}
