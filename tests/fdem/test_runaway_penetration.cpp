// Runaway penetration as an instability criterion of FEM/DEM runs (fdem/runaway_penetration.hpp): a
// penalty too soft for the impact is tunnelled while the energy stays conserved, so only this
// criterion can stop the run; healthy collisions stay far below its threshold.
#include <gtest/gtest.h>

#include "scenes/particle_block_impact.hpp"

namespace asperity::run {
namespace {

// The default penalty (α = 10) at 1 and 100 m/s: the deepest overlap stays a few per cent of the
// way to an element's centroid (measured 0.003 and 0.03), an order of magnitude under the 0.5 of
// the criterion, and the runs are ok.
TEST(RunawayPenetration, HealthyCollisionsStayFarBelowTheThreshold) {
  for (const double speed : {1.0, 100.0}) {
    const RunResult r = impact("healthy", "fem", speed, 0, false, speed < 10 ? 5e-4 : 2e-4);
    EXPECT_EQ(r.status, "ok") << speed << " m/s: " << r.message;
    EXPECT_LT(r.summary["max_penetration_ratio"].get<double>(), 0.05) << speed << " m/s";
  }
}

// A penalty 5e5 times softer than the default (1e6 Pa) still holds a rigid particle at 1 m/s:
// it bounces elastically (restitution > 0.98: the contact is conservative and resolved in
// hundreds of steps) with its deepest point about a quarter of the way to the centroid.
TEST(RunawayPenetration, SoftPenaltyHoldsASlowImpact) {
  const RunResult r = impact("soft-slow", "rigid", 1.0, 1e6, false, 0.03);
  EXPECT_EQ(r.status, "ok") << r.message;
  EXPECT_LT(r.summary["max_penetration_ratio"].get<double>(), 0.5);
  EXPECT_GT(r.summary["restitution"].get<double>(), 0.98);
}

// At 50 m/s the same penalty cannot stop the particle within its elements: without the criterion
// the run ends "ok", energy conserved, with the particle out through the bottom of the block
// (restitution −1.0). The criterion stops it as unstable with one line naming both bodies and
// the time.
TEST(RunawayPenetration, SoftPenaltyFastImpactIsFlagged) {
  const RunResult r = impact("soft-fast", "rigid", 50.0, 1e6, false, 0.003);
  EXPECT_EQ(r.status, "unstable");
  EXPECT_EQ(r.message.find('\n'), std::string::npos) << r.message;
  EXPECT_EQ(r.message.rfind(R"(runaway penetration: bodies "particle" and "block" overlap )", 0),
            0u)
      << r.message;
  EXPECT_NE(r.message.find("(limit 0.5) at t = "), std::string::npos) << r.message;
  EXPECT_GE(r.summary["max_penetration_ratio"].get<double>(), 0.5);
}

// A block 1 m deep has elements hundreds of times larger than the particle's, so the particle can
// sink its own size into a far too soft penalty (6e4 Pa: 1.2e-6 E, just above the scene loader's
// lower bound of 1e-6 E; at 3 m/s, 9 times the kinetic energy of 1 m/s, for a penalty 6 times the
// 1e4 Pa this test used before that bound) while the overlap is still a small part of the block
// element's height:
// the second half of the criterion, the particle's centre inside the block, stops it.
TEST(RunawayPenetration, BodySinkingIntoABlockIsFlaggedByItsCentre) {
  const RunResult r = impact("sinking", "rigid", 3.0, 6e4, true, 0.05);
  EXPECT_EQ(r.status, "unstable");
  EXPECT_EQ(r.message.rfind(R"(runaway penetration: body "particle" passed through "block")", 0),
            0u)
      << r.message;
  EXPECT_NE(r.message.find(" at t = "), std::string::npos) << r.message;
  EXPECT_LT(r.summary["max_penetration_ratio"].get<double>(), 0.5);
}

// A step so long (8 ms: 80 mm at 10 m/s, the block is 20 mm deep) that the particle jumps from
// above the block to below it without any step seeing a contact: the run would end
// "no_contact". Its centre's path through the step crossed the block, which stops it.
TEST(RunawayPenetration, BodyJumpingThroughABlockInOneStepIsFlagged) {
  const RunResult r =
      impact("jump", "rigid", 10.0, 0, false, 0.016, R"(, "dt": 0.008, "allow_unsafe_dt": true)");
  EXPECT_EQ(r.status, "unstable");
  EXPECT_EQ(r.message.rfind(R"(runaway penetration: body "particle" passed through "block")", 0),
            0u)
      << r.message;
  EXPECT_EQ(r.summary["max_penetration_ratio"].get<double>(), 0);  // no contact was ever seen
}

}  // namespace
}  // namespace asperity::run
