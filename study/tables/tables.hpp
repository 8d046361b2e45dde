// The study's tables, one unit each (docs/study.md, "Tables"), in the order write_tables calls
// them. Each reads the loaded cases (study_cases.hpp) and writes its file atomically into DIR.
#pragma once

#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "study/study_run.hpp"
#include "study/tables/study_cases.hpp"

namespace asperity::study::tables {

// cases.csv: one row per case, its measures, errors against the same model's reference
// resolution and against the fem reference (same placement).
void write_cases_table(const StudyCases& s, const std::filesystem::path& dir);

// Each model and resolution's force curve (the coarse default for fem) against the converged fem
// reference curve (same particle, placement).
struct Classification {
  std::string particle;
  ModelKind model;
  Placement placement;
  long resolution;
  double lag, lag_rel, duration_ratio;  // lag_rel, duration_ratio NaN without a reference duration
  // The first-contact time's shift from the reference's over the reference's contact duration
  // (cases.csv first_contact_shift_fem): what "shifted" means.
  double onset_shift_rel = std::nan("");
  double skewness, skewness_reference;
  std::string cls;  // classify()
};
std::vector<Classification> classify_resolutions(const StudyCases& s);
// classification.csv: a row per Classification.
void write_classification_table(const std::vector<Classification>& rows,
                                const std::filesystem::path& dir);
// particle_classes.csv: per particle, model and placement, every class met at any resolution
// and the coarsest resolution's class.
void write_particle_classes_table(const std::vector<Classification>& rows,
                                  const std::filesystem::path& dir);

// references.csv: per particle and placement, the reference (the limit of the fem sequence at the
// finest resolution), the order its peak force was extrapolated at (observed or assumed) and,
// per metric, the two terms of its uncertainty and their quadrature sum (docs/study.md, "The
// reference"): which dominates, discretization or geometry.
void write_references_table(const StudyCases& s, const std::filesystem::path& dir);

// Median CPU per resolution across particles fitted as t = C N^p (least squares, log–log).
struct CpuFit {
  ModelKind model;
  Placement placement;
  double exponent, coefficient;
  long points;
};
std::vector<CpuFit> fit_cpu(const StudyCases& s);
// cpu_fit.csv: a row per fit.
void write_cpu_fit_table(const std::vector<CpuFit>& fits, const std::filesystem::path& dir);

// A candidate (model and resolution) at one placement: |error| against the fem reference over
// the particles, median and 90th percentile per metric, and its median CPU.
struct CandidateStats {
  Placement placement;
  ModelKind model;
  long resolution;           // 0 for the sphere
  int level = 0;             // fem: 0 coarse, k the k-th refined element size
  double relative_size = 0;  // that size over the equivalent radius
  int particles = 0;
  std::map<std::string, std::pair<double, double>> err;  // metric → (median, p90)
  double cpu = std::nan("");
};
// Every candidate with at least one particle's errors, by placement (none without fem).
std::vector<CandidateStats> candidate_stats(const StudyCases& s);
// The reference's uncertainty over the particles of a placement, per metric (kMetrics and
// "peak_force+impulse"): (median, p90).
std::map<std::string, std::pair<double, double>> reference_uncertainty(const StudyCases& s,
                                                                       Placement pl);
// candidates.csv: a row per candidate.
void write_candidates_table(const std::vector<CandidateStats>& stats,
                            const std::filesystem::path& dir);

// guidelines.csv and guidelines.json: for each tolerance, metric and statistic, the cheapest
// candidate that meets it; the JSON adds the range of particles and impacts measured (recommend
// warns outside). Returns guidelines.json.
OJson write_guidelines(const StudyCases& s, const std::vector<CandidateStats>& stats,
                       const std::filesystem::path& dir);

// The published study this one repeats (data/study/zhang_zsaki_2019.json), as the summary
// reports it. Throws InputError naming the file and key when one is missing or not a number.
OJson read_published_study(const std::filesystem::path& file);

// study_summary.json: counts, total CPU (every done case, whenever it ran) and by model, the
// wall time of the runs that computed the cases (added to the folder's earlier summary), the
// fem CPU growth and fits, beside the published study. Returns it.
OJson write_study_summary(const StudyCases& s, const std::vector<CpuFit>& fits,
                          const OJson& published, const StudyOutcome& run,
                          const std::filesystem::path& dir);

}  // namespace asperity::study::tables
