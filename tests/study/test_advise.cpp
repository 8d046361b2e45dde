// `asperity advise`'s choice (study/advise.hpp) on constructed candidates: the cheapest within
// the tolerance at every orientation, else "none of the studied" with the smallest worst error,
// and a candidate measured at fewer orientations than the others never chosen. The advice copies
// the candidates' numbers (no arithmetic), so they are compared exactly.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "study/advise.hpp"

namespace asperity::study {
namespace {

AdviceCandidate candidate(ModelKind m, long n, int level, double median, double worst, double cpu,
                          int orientations = 4) {
  return {.model = m,
          .resolution = n,
          .level = level,
          .relative_size = level > 0 ? 0.04 : 0.0,
          .orientations = orientations,
          .error_median = median,
          .error_worst = worst,
          .cpu = cpu};
}

const std::vector<AdviceCandidate> kField = {
    candidate(ModelKind::sphere, 0, 0, 0.15, 0.30, 0.01),
    candidate(ModelKind::rigid, 250, 0, 0.03, 0.06, 0.5),
    candidate(ModelKind::fem, 2000, 2, 0.02, 0.03, 60.0),
    // Cheap and close, but measured at 3 of the 4 orientations (one failed): not comparable.
    candidate(ModelKind::rigid, 100, 0, 0.01, 0.01, 0.1, 3)};

TEST(Advise, CheapestWithinTheToleranceAtEveryOrientation) {
  // 5 %: the rigid polyhedron's worst orientation (6 %) is out, so the refined fem.
  const Advice five = advise(kField, "peak_force", 0.05, {0.004, 0.009});
  EXPECT_TRUE(five.met);
  EXPECT_EQ(five.pick.model, ModelKind::fem);
  EXPECT_EQ(five.pick.error_worst, 0.03);
  EXPECT_EQ(five.reference_uncertainty_worst, 0.009);
  // 10 %: the rigid polyhedron at 250 triangles, cheaper.
  const Advice ten = advise(kField, "peak_force", 0.10, {0.004, 0.009});
  EXPECT_TRUE(ten.met);
  EXPECT_EQ(ten.pick.model, ModelKind::rigid);
  EXPECT_EQ(ten.pick.resolution, 250);
}

TEST(Advise, NoneWithinNamesTheSmallestWorstError) {
  const Advice two = advise(kField, "impulse", 0.02, {0.004, 0.009});
  EXPECT_FALSE(two.met);
  EXPECT_EQ(two.pick.model, ModelKind::fem);  // 3 %, the smallest worst error of the four-ways
  EXPECT_EQ(two.pick.error_worst, 0.03);
}

TEST(Advise, NoCandidateGivesNoPick) {
  const Advice a = advise({}, "peak_force", 0.05, {std::nan(""), std::nan("")});
  EXPECT_FALSE(a.met);
  EXPECT_EQ(a.pick.orientations, 0);
}

}  // namespace
}  // namespace asperity::study
