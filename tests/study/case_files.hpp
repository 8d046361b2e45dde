// Hand-made study folders for the table tests (test_study_tables.cpp, test_study_reference.cpp):
// a scratch folder and a finished case written as `asperity study` leaves it, so each test states
// only the measures it feeds the tables.
#pragma once

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "study/study_run.hpp"
#include "study/tables/tables.hpp"

namespace asperity::study::test {

// An empty folder TMP/asperity_PREFIX_NAME (an earlier test's removed).
inline std::filesystem::path scratch(const std::string& prefix, const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("asperity_" + prefix + "_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// The measures of a finished case (summary.json) and the study's facts about it (case.json).
struct CaseFiles {
  double peak = 0, impulse = 0, duration = 0;  // N, N·s, s
  double first_contact = 5e-5;                 // s
  double cpu_seconds = 1.0;
  std::optional<double> element_size_rel;  // case.json's refined size over R, when written
  std::optional<double> peak_filtered;     // summary.json's peak_force_filtered, N, when written
};

// A finished case of `study`: case.json (the done marker, with the study's facts) and summary.json
// with the measures, in the case's folder (case_dir).
inline void write_case(const std::filesystem::path& study, const CaseKey& k, const CaseFiles& f) {
  const std::filesystem::path dir = case_dir(study, k);
  std::filesystem::create_directories(dir);
  tables::OJson summary{{"status", "ok"},
                        {"peak_force", f.peak},
                        {"impulse", f.impulse},
                        {"contact_duration", f.duration},
                        {"first_contact_time", f.first_contact}};
  if (f.peak_filtered) summary["peak_force_filtered"] = *f.peak_filtered;
  std::ofstream(dir / "summary.json") << summary.dump();
  tables::OJson c{{"start_gap", 1e-4}, {"cpu_seconds", f.cpu_seconds}};
  if (f.element_size_rel) c["element_size_rel"] = *f.element_size_rel;
  std::ofstream(dir / "case.json") << c.dump();
}

}  // namespace asperity::study::test
