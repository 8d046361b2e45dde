// A time step no sliver sets (issue 11, item 5), on a sample of the full study's meshes: the
// penalty contact at a scene's default penalty pulling the predicted step at most 2× below the
// elements' own limit. Every particle and resolution of the full study against h/c (h the
// shortest surface edge, c the P-wave speed): reports/fem/mesh_step.md (mesh_step_survey).
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "study/mesh_step_survey.hpp"
#include "study/study_def.hpp"

namespace asperity::study {
namespace {

// Particles the bound was not tuned on (neither the benchmark's particle nor the default study's
// first ten), one of each kind of the set (even entries ballast-like and angular, odd rock-like,
// flat and elongated) at the coarsest, a middle and the reference resolution.
//
// What holds and is asserted: every mesh is made (a mesher failure would be this row's error),
// and at a scene's default penalty the contact pulls the predicted step at most 2× below the
// elements' limit (fdem::limit_penalty; at α = 10 as asked it was 1.1–4.3× on the full set).
// What does not hold and is therefore not asserted: dt_element·c/h ≥ 1/3 (the full set: 0.04 to
// 3.0, reports/fem/mesh_step.md): surface slivers and short simplified edges still set the
// element step on some meshes; the mesher does not repair them yet.
TEST(MeshStep, ContactCostsAtMostTwiceTheElementStep) {
  const StudyDef def = load_study(std::string(ASPERITY_SOURCE_DIR) + "/data/study/full.json");
  for (const std::size_t particle : {16UL, 33UL, 42UL}) {
    for (const MeshStep& m : mesh_steps(def, particle, {100, 500, 2000})) {
      SCOPED_TRACE(m.particle + " at " + std::to_string(m.faces) + " triangles");
      ASSERT_EQ(m.error, "");
      // The item's bound, to the regula falsi's last step (it stops at or below the factor).
      EXPECT_LE(m.limited_factor(), 2.0 + 1e-9);
      // And the penalty is not lowered further than it must be: within 10 % of the factor
      // (six Illinois steps) wherever it was lowered at all.
      if (m.alpha_limited < 10) {
        EXPECT_GE(m.limited_factor(), 1.8);
      }
      // α = 10 as asked is what it was: limited only by lowering.
      EXPECT_GE(m.contact_factor(), m.limited_factor() - 1e-9);
    }
  }
}

}  // namespace
}  // namespace asperity::study
