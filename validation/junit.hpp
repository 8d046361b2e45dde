// JUnit XML for CI (GitLab, GitHub, Jenkins show each <testcase>): one per case and check, the
// measured value, the expected value and the tolerance in the failure message.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace asperity::validation {

struct JUnitCase {
  std::string classname;  // the case (or scene) name
  std::string name;       // the check, e.g. "peak_force"
  double seconds = 0;     // CPU time the case cost (shared by its checks)
  bool failed = false;    // a check that missed its expectation: <failure>
  bool error = false;     // the run itself failed (a peer or solver failure): <error>
  bool skipped = false;   // not run, for the reason in `message`: <skipped>
  std::string message;    // one line: measured, expected, tolerance
  std::string details;    // the tolerance's reason, or the failure's text
};

// Writes `file` (through a temporary and a rename): one <testsuite name=suite>.
void write_junit(const std::filesystem::path& file, const std::string& suite,
                 const std::vector<JUnitCase>& cases);

}  // namespace asperity::validation
