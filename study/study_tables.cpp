// write_tables: the study's tables, one unit each (study/tables/), over the cases loaded once.
#include "study/study_tables.hpp"

#include "study/tables/tables.hpp"

namespace asperity::study {
namespace fs = std::filesystem;

StudyTables write_tables(const StudyDef& def, const fs::path& dir, const StudyOutcome& run) {
  // The published figures first: a bad reference file stops the tables before any is written.
  const tables::OJson published = tables::read_published_study(ASPERITY_PUBLISHED_STUDY);
  const tables::StudyCases cases = tables::load_study_cases(def, dir);
  tables::write_cases_table(cases, dir);
  tables::write_references_table(cases, dir);
  tables::write_unreferenced_table(cases, dir);
  tables::write_discretization_table(cases, dir);
  tables::write_geometry_tables(tables::geometry_term(tables::converged_answers(cases)), dir);
  const std::vector<tables::Classification> classes = tables::classify_resolutions(cases);
  tables::write_classification_table(classes, dir);
  tables::write_particle_classes_table(classes, dir);
  const std::vector<tables::CpuFit> fits = tables::fit_cpu(cases);
  tables::write_cpu_fit_table(fits, dir);
  const std::vector<tables::CandidateStats> stats = tables::candidate_stats(cases);
  tables::write_candidates_table(stats, dir);
  tables::write_answer_tables(cases, stats, dir);
  StudyTables out{.cases = static_cast<int>(cases.cases.size() + cases.source_cases.size()),
                  .done = cases.done,
                  .failed = cases.failed};
  out.guidelines = tables::write_guidelines(cases, stats, dir);
  out.summary = tables::write_study_summary(cases, fits, published, run, dir);
  return out;
}

}  // namespace asperity::study
