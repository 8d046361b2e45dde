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
// finest resolution, or of the source reference's levels), the order its peak force was
// extrapolated at (observed or assumed) and, per metric, the terms of its uncertainty and their
// quadrature sum (docs/study.md, "The reference"): which dominates, discretization or geometry;
// for the source reference per metric also the order and the patch check's change (the geometry
// term empty: the geometry is the particle's), and which levels its limit is from, the finest
// size and the CPU of all its levels.
void write_references_table(const StudyCases& s, const std::filesystem::path& dir);

// unreferenced.csv: per particle and placement with no reference, why (the cases its reference
// needed that are not usable, with their status and the run's message).
void write_unreferenced_table(const StudyCases& s, const std::filesystem::path& dir);

// The geometry term (docs/study.md, "The geometry term"): for a study refining two or more
// resolutions N, the converged answer at each N (the Richardson limit of its refined levels)
// isolates the particle's shape from the element size; along N those answers form a second
// sequence, in the surface edge length s ~ N^-1/2, extrapolated N -> infinity by richardson().
// One particle and placement's converged answer at one N: the limit per metric and its
// estimated error (relative).
struct ConvergedAnswer {
  long resolution = 0;
  Measures limit;
  FemErrors limit_error;
};
// The metrics the geometry term follows (kMetrics without the first-contact time, which is the
// free flight's).
inline constexpr std::size_t kGeometryMetricCount = 3;
// The tolerances "is N enough?" is answered at.
inline constexpr double kGeometryTolerances[] = {0.01, 0.02, 0.05};
// geometry.csv: a particle's converged answer at one N for one metric (resolution 0: the
// N -> infinity row, whose value is the limit and limit_error its estimated error).
struct GeometryRow {
  std::string particle, placement;
  std::size_t metric = 0;  // index into kMetrics
  long resolution = 0;
  double value = std::nan(""), discretization_error = std::nan(""), change = std::nan(""),
         order_observed = std::nan(""), error_vs_limit = std::nan(""), limit_error = std::nan("");
};
// geometry_answer.csv: is the finest-but-one N enough, per particle (and "median") and metric.
struct GeometryAnswerRow {
  std::string particle, placement;
  std::size_t metric = 0;
  long resolution = 0;
  double value = std::nan(""), limit = std::nan(""), limit_error = std::nan(""),
         error = std::nan(""), last_change = std::nan(""), error_estimate = std::nan(""),
         discretization_error = std::nan("");
  std::string estimate_from;  // "limit", "last change" or (median) "limit or last change"
  std::string within[3];      // per kGeometryTolerances: yes, no, likely, undecided
};
struct GeometryTerm {
  std::vector<GeometryRow> sequence;
  std::vector<GeometryAnswerRow> answer;  // per particle, then the medians per placement
};
// The converged answers of every (particle, placement name) whose refined levels all ran, by N.
std::map<std::pair<std::string, std::string>, std::vector<ConvergedAnswer>> converged_answers(
    const StudyCases& s);
// The sequence in N and the answer from the converged answers (each particle's by ascending N):
// a particle with fewer than two N is left out.
GeometryTerm geometry_term(
    const std::map<std::pair<std::string, std::string>, std::vector<ConvergedAnswer>>& answers);
// geometry.csv and geometry_answer.csv, when any particle has converged answers at two or more
// N; otherwise neither (an earlier run's are removed).
void write_geometry_tables(const GeometryTerm& g, const std::filesystem::path& dir);

// discretization.csv: per placement and resolution N, over the particles whose fem sequence at N
// was refined: the coarse case's discretization error (against the sequence's limit), the finest
// level's, the limit's estimated error, the geometry effect (the limit at N against the limit at
// the finest N), the last refinement's change and the sequence's CPU per particle (median, p90,
// worst); medians and p90s as quantile() (type 7).
void write_discretization_table(const StudyCases& s, const std::filesystem::path& dir);

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

// "The answer" (docs/study.md, "The answer"): for each tolerance, metric and statistic over the
// particles, the cheapest studied model, resolution and element size whose error against the
// reference meets it, with its error, the reference's uncertainty (same statistic) and its CPU;
// where none meets it, "none of the studied" with the smallest error. The reference's uncertainty
// is reported beside the error, never a reason to leave a row unanswered.
inline constexpr double kAnswerTolerances[] = {0.02, 0.05, 0.10};
// "A few hundred triangles", the published study's question (Zhang & Zsaki 2019 ran 100 to 1000
// and asked whether a few hundred suffice): at most this many surface triangles.
inline constexpr long kFewHundred = 500;
struct AnswerRow {
  Placement placement = Placement::lowest;
  std::string metric;               // kMetrics or "peak_force+impulse"
  double tolerance = std::nan("");  // few_hundred: the smallest kAnswerTolerances met, NaN: none
  bool p90 = false;                 // the statistic: median (half the particles) or p90
  bool met = false;  // false: none of the studied meets it; `pick` has the best error
  const CandidateStats* pick = nullptr;
  double error = std::nan(""), reference_uncertainty = std::nan("");
};
// The metrics the answer gives at a placement: kMetrics and "peak_force+impulse", less the one
// that is 0 by construction: the first-contact time under `lowest` (every model starts with its
// lowest point at the same gap, so each touches at the same time).
std::vector<std::string> answer_metrics(Placement pl);
// Per answer_metrics(pl), kAnswerTolerances and statistic (median, p90), from the candidates at
// pl and the reference's uncertainty (reference_uncertainty()); a metric no candidate has is
// left out.
std::vector<AnswerRow> answer_rows(
    const std::vector<CandidateStats>& stats, Placement pl,
    const std::map<std::string, std::pair<double, double>>& uncertainty);
// "Is a few hundred triangles enough?": per answer_metrics(pl) and statistic, the candidate with a
// surface of at most kFewHundred triangles (spheres have none) with the smallest error, `met`
// when that error is within the largest of kAnswerTolerances, `tolerance` the smallest it meets.
std::vector<AnswerRow> few_hundred_rows(
    const std::vector<CandidateStats>& stats, Placement pl,
    const std::map<std::string, std::pair<double, double>>& uncertainty);
// answer.csv and few_hundred.csv: the rows above for every placement of the study.
void write_answer_tables(const StudyCases& s, const std::vector<CandidateStats>& stats,
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
