// The study's tables from its case folders: per-case measures and errors, the classification of
// each particle's response across resolutions, the CPU-cost fit and the guidelines. Written by
// `asperity study` at its end and read by `asperity report` and `asperity recommend`.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include "study/study_def.hpp"
#include "study/study_run.hpp"

namespace asperity::study {

struct StudyTables {
  int cases = 0, done = 0, failed = 0;
  nlohmann::ordered_json summary;     // study_summary.json
  nlohmann::ordered_json guidelines;  // guidelines.json
};

// Reads DIR/cases/** and writes DIR/cases.csv, classification.csv, particle_classes.csv,
// cpu_fit.csv, guidelines.csv, guidelines.json and study_summary.json (each atomically).
// `run` adds this run's wall and CPU time to the summary.
StudyTables write_tables(const StudyDef& def, const std::filesystem::path& dir,
                         const StudyOutcome& run);

}  // namespace asperity::study
