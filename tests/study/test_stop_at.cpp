// A caller's deadline (`advise --budget`, `study --stop-after`): the time loop stops at it with no
// result, and a study postpones what it cut, writing nothing of it as done, so that the next run
// does it and ends where an uninterrupted run would have.
#include <chrono>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "scenes/dem_scenes.hpp"
#include "solver/io/json_file.hpp"
#include "solver/run/run_scene.hpp"
#include "study/study_def.hpp"
#include "study/study_run.hpp"

namespace asperity::study {
namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Files a case leaves as done (case.json) or failed (failed.json) under DIR/cases.
int marked_cases(const fs::path& out, const char* marker) {
  int n = 0;
  if (!fs::exists(out / "cases")) return 0;
  for (const auto& f : fs::recursive_directory_iterator(out / "cases")) {
    n += f.path().filename() == marker ? 1 : 0;
  }
  return n;
}

TEST(StopAt, TheTimeLoopStopsAtTheDeadlineWithNoResult) {
  // A Hertz sphere on a plane whose auto step (1/100 of the contact) makes thousands of steps:
  // past the deadline from the start, the loop throws at its first look at the clock (step 256).
  const scene::SceneDef s = asperity::test::sphere_on_plane(1.0, 1e-3, scene::ContactLaw::hertz);
  const run::RunResult whole = run::run_scene(s, {.keep_rows = false});
  ASSERT_EQ(whole.status, "ok");
  ASSERT_GT(whole.summary.at("steps").get<long>(), 256) << "too few steps to test the stop";
  try {
    run::run_scene(s, {.keep_rows = false, .stop_at = Clock::now()});
    FAIL() << "the run went on past its deadline";
  } catch (const run::RunStopped& e) {
    EXPECT_NE(std::string(e.what()).find("stopped at step 256 of"), std::string::npos) << e.what();
  }
  // A deadline an hour away changes nothing: the same steps and peak, to the bit.
  const run::RunResult later =
      run::run_scene(s, {.keep_rows = false, .stop_at = Clock::now() + std::chrono::hours(1)});
  EXPECT_EQ(later.summary.at("steps"), whole.summary.at("steps"));
  EXPECT_EQ(later.summary.at("peak_force"), whole.summary.at("peak_force"));
}

TEST(StopAt, AStudyPastItsDeadlinePostponesEverythingAndTheNextRunDoesIt) {
  const fs::path work = fs::temp_directory_path() / "asperity_stop_at_study";
  fs::remove_all(work);
  // 2 particles x 2 placements of the sphere model: 4 cases, about 2 s of CPU.
  const StudyDef def =
      load_study(fs::path(ASPERITY_SOURCE_DIR) / "tests/study/sphere_only_study.json");
  const StudyOutcome stopped =
      run_study(def, work, {.jobs = 1, .quiet = true, .stop_at = Clock::now()});
  EXPECT_EQ(stopped.cases, 4);
  EXPECT_EQ(stopped.postponed, 4);
  EXPECT_EQ(stopped.ran, 0);
  EXPECT_EQ(stopped.failed, 0);
  // Postponed is neither done nor failed: no marker, so nothing is taken as a result.
  EXPECT_EQ(marked_cases(work, "case.json"), 0);
  EXPECT_EQ(marked_cases(work, "failed.json"), 0);
  EXPECT_EQ(unfinished_cases(def, work), 4);

  const StudyOutcome resumed = run_study(def, work, {.jobs = 1, .quiet = true});
  EXPECT_EQ(resumed.postponed, 0);
  EXPECT_EQ(resumed.ran, 4);
  EXPECT_EQ(resumed.failed, 0);
  EXPECT_EQ(marked_cases(work, "case.json"), 4);
  EXPECT_EQ(unfinished_cases(def, work), 0);
  fs::remove_all(work);
}

}  // namespace
}  // namespace asperity::study
