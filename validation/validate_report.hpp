// The report of `asperity validate`: DIR/results.csv (one row a check), DIR/report.md (the same
// as a table, with each check's tolerance) and DIR/validation.json (every case's check), in the
// cases' order.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace asperity::validation {

// One case as the report sees it: its check (validation::to_json of its CaseResult) and the
// CPU seconds its run took.
struct CaseOutcome {
  nlohmann::ordered_json check;
  double cpu_seconds = 0;
};

// Writes the three files (each through a temporary and a rename); `solved_by` names who solved
// the cases ("asperity", "the peer yade", "the command `...`").
void write_validate_report(const std::vector<CaseOutcome>& cases, const std::filesystem::path& out,
                           const std::string& solved_by);

}  // namespace asperity::validation
