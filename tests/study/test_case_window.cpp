// A contact still open when a case's window ends is no result (study_run.cpp, run_case): the case
// runs again in a window twice as long, as the same run continued, and fails when it is still open
// after the last doubling.
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "solver/io/json_file.hpp"
#include "study/study_def.hpp"
#include "study/study_run.hpp"

namespace asperity::study {
namespace {
namespace fs = std::filesystem;

// A one-particle, one-placement sphere study in a window of `duration` s, `gap` m above the block.
StudyDef one_case_study(double duration, double gap = 1e-4) {
  StudyDef def = load_study(fs::path(ASPERITY_SOURCE_DIR) / "tests/study/sphere_only_study.json");
  def.particles.resize(1);
  def.placements = {Placement::lowest};
  def.duration = duration;
  def.gap = gap;
  return def;
}

// That study's one case, run into a fresh `work`.
struct OneCase {
  StudyOutcome outcome;
  nlohmann::json summary, record;
  bool failed = false;
  std::string message;
};

OneCase run_one(const fs::path& work, double duration, double gap = 1e-4) {
  const StudyDef def = one_case_study(duration, gap);
  fs::remove_all(work);
  OneCase r;
  r.outcome = run_study(def, work, {.jobs = 1, .quiet = true});
  for (const auto& f : fs::recursive_directory_iterator(work / "cases")) {
    if (f.path().filename() == "case.json") {
      r.record = io::read_json_file(f.path());
      r.summary = io::read_json_file(f.path().parent_path() / "summary.json");
    } else if (f.path().filename() == "failed.json") {
      r.failed = true;
      r.message = io::read_json_file(f.path()).at("message").get<std::string>();
    }
  }
  return r;
}

TEST(CaseWindow, AContactTheWindowCutsRunsOnInADoubledWindowAsTheSameRun) {
  const fs::path work = fs::temp_directory_path() / "asperity_case_window";
  // The sphere (0.05 m, rock on the stiff block, 2 m/s) reaches the block after the 0.1 mm gap,
  // 50 µs, and its Hertz contact lasts about 126 µs (Johnson 1985, eq. 11.24): a 100 µs window
  // cuts it, 200 µs holds it, and 800 µs holds it with room to spare.
  const OneCase cut = run_one(work, 100e-6);
  const OneCase whole = run_one(work, 800e-6);
  ASSERT_FALSE(cut.failed) << cut.message;
  ASSERT_FALSE(whole.failed) << whole.message;
  EXPECT_EQ(cut.record.at("window_doublings"), 1);
  EXPECT_DOUBLE_EQ(cut.record.at("duration").get<double>(), 200e-6);
  EXPECT_EQ(whole.record.at("window_doublings"), 0);
  // The doubled window's run is the long window's, to the bit, up to its end: the same peak,
  // impulse, contact duration and first contact (the sphere model's step and sampling do not
  // depend on the window).
  for (const char* k : {"peak_force", "impulse", "contact_duration", "first_contact_time"}) {
    EXPECT_EQ(cut.summary.at(k), whole.summary.at(k)) << k;
  }
  EXPECT_GT(cut.summary.at("peak_force").get<double>(), 0.0);
  // Resumed, the case is done: its stored window is one of the doublings and its contact closed.
  const OneCase first = run_one(work / "again", 100e-6);
  ASSERT_EQ(first.record.at("window_doublings"), 1);
  const StudyOutcome resumed =
      run_study(one_case_study(100e-6), work / "again", {.jobs = 1, .quiet = true});
  EXPECT_EQ(resumed.skipped, 1);
  EXPECT_EQ(resumed.ran, 0);
  fs::remove_all(work);
}

TEST(CaseWindow, AContactStillOpenAfterTheLastDoublingFailsTheCase) {
  const fs::path work = fs::temp_directory_path() / "asperity_case_window_open";
  // With a 0.1 µm gap the contact (about 126 µs) starts at once; a 10 µs window doubled three
  // times, 80 µs, still ends inside it.
  const OneCase open = run_one(work, 10e-6, 1e-7);
  EXPECT_TRUE(open.failed);
  EXPECT_NE(open.message.find("the contact is still open at the end of the window, 8e-05 s"),
            std::string::npos)
      << open.message;
  EXPECT_EQ(open.outcome.failed, 1);
  fs::remove_all(work);
}

}  // namespace
}  // namespace asperity::study
