// What every table of a study reads: its case folders loaded once (status, summary.json,
// mesh.json, CPU), looked up by (particle, model, resolution, placement), each case's error
// against the fem reference, and the one way a table is written as CSV.
#pragma once

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/core/richardson.hpp"
#include "study/study_def.hpp"
#include "study/study_run.hpp"

namespace asperity::study::tables {

using OJson = nlohmann::ordered_json;

struct CaseData {
  CaseKey key;
  std::string status;  // "ok", "unstable", "no_contact", "failed", "missing"
  std::string message;
  OJson summary, mesh;
  OJson record;  // case.json: the study's facts of the case (cpu_seconds, element_size, start_gap)
  double cpu = std::nan("");
  double start_gap = std::nan("");
  std::filesystem::path dir;
};

// The measures the guidelines compare (docs/study.md, "Guidelines"): peak force, impulse and
// contact duration as relative errors; the first-contact time as its shift over the reference's
// contact duration (the start gap makes the time itself mostly free flight, so its relative
// error would say nothing about the pulse).
inline constexpr const char* kMetrics[] = {"peak_force", "impulse", "contact_duration",
                                           "first_contact_time"};
inline constexpr std::size_t kMetricCount = 4;

// A case's errors against the reference of its particle and placement, per kMetrics; NaN where
// either is not usable.
struct FemErrors {
  double peak = std::nan(""), impulse = std::nan(""), duration = std::nan(""),
         arrival = std::nan("");
  double metric(std::size_t m) const {
    return m == 0 ? peak : m == 1 ? impulse : m == 2 ? duration : arrival;
  }
};

// The measured values a reference supplies per kMetrics (the first-contact time as a time).
struct Measures {
  double peak = std::nan(""), impulse = std::nan(""), duration = std::nan(""),
         first_contact = std::nan("");
};

// The assumed order of the fem peak force, impulse and contact duration under the study's graded
// refinement, where a sequence has only two refined levels: the orders the Hertz gate measured on
// the same grading (reports/fem/hertz_convergence.md, "block, graded" at a/R 0.05-0.15: peak
// 1.16-2.68, duration 1.23-3.18), bracketed as [1.2, 2.7].
inline constexpr double kAssumedOrderLow = 1.2, kAssumedOrderHigh = 2.7;
// An observed order (three refined levels) outside this range is not trusted (oscillating or
// pre-asymptotic levels): the two finest levels are extrapolated with the assumed bracket. The
// range, and why, is the cross-checks' (solver/core/richardson.hpp).
inline constexpr double kObservedOrderMin = kTrustedOrderMin, kObservedOrderMax = kTrustedOrderMax;
// Roache's safety factor on the error of a three-level extrapolation at its observed order
// (Roache 1998, "Verification and Validation in Computational Science", GCI with Fs = 1.25).
inline constexpr double kSafetyObserved = 1.25;

// A Richardson extrapolation of one metric along the refined levels (docs/study.md,
// "The reference"): the limit, its estimated error (relative to the limit), the order used, and
// whether that order was observed (three levels, monotone, in range) or assumed (the bracket).
// Either way the limit is the finest value plus `weight` times the last change,
// limit = v[n−1] + weight (v[n−1] − v[n−2]): weight = 1/((s[n−2]/s[n−1])^p − 1) at an observed
// order p, the mean of the bracket's two such weights when assumed (extrapolate_like).
// The convergence reports' rule is solver/core/richardson.hpp: three levels at one constant
// ratio, the order they show printed whatever it is, no bracket, no safety factor; on levels that
// converge at an order in the trusted range the two give the same limit (test_study_tables.cpp).
struct Extrapolation {
  double limit = std::nan("");
  double error = std::nan("");  // relative: |estimate − limit| bound / |limit|
  double order = std::nan("");  // observed; or the bracket's middle when assumed
  bool observed = false;
  double weight = std::nan("");  // of the last change, as above
  // The order of the last three levels' changes whenever they fall monotonically, in the trusted
  // range or not (NaN: fewer than three levels, or changes that oscillate or grow): an assumed
  // order beside an order of changes far below the bracket says the levels are not asymptotic.
  double changes_order = std::nan("");
};
// values[k] at element sizes sizes[k] (descending, at least two): with three or more, the
// observed order of the last three when they change monotonically at an order within
// [kObservedOrderMin, kObservedOrderMax], the limit at it and kSafetyObserved × its last
// correction as the error; otherwise the two finest levels extrapolated at both ends of the
// assumed bracket, the limit their mean and the error half their spread.
Extrapolation richardson(const std::vector<double>& sizes, const std::vector<double>& values);
// The limit of another sequence `values` at the same sizes extrapolated with `like`'s order and
// weight (not its own): values[n−1] + like.weight (values[n−1] − values[n−2]); NaN when `like`
// has no weight or `values` has fewer than two finite levels. A sequence that differs from the
// one `like` came from by a constant offset gets a limit that differs by exactly that offset,
// whatever its own changes would say (the source reference's patch check, source_reference.hpp).
double extrapolate_like(const std::vector<double>& values, const Extrapolation& like);

// √(a² + b²): the one quadrature of a reference's uncertainty terms (the finest reference's
// discretization and geometry, the source reference's discretization, patch check and filter,
// source_reference.hpp). A term that is not finite counts 0, deliberately: a term that was not
// measured (the patch check not run, no coarser refined resolution for the geometry term) adds
// nothing, as the references' tables have always summed; a reference whose own limit is not
// finite has no value for its uncertainty to qualify.
inline double quadrature_sum(double a, double b) {
  return std::hypot(std::isfinite(a) ? a : 0.0, std::isfinite(b) ? b : 0.0);
}

// The fem refinement sequence of one (particle, resolution, placement): its answer (the finest
// usable level; the coarse case when the study refines none), whether the last refinement moved
// the peak force by less than the study's tolerance, per metric the change between the two
// finest levels, and the limit: the Richardson extrapolation of its refined levels (the answer's
// own values, with error = the last change, when fewer than two refined levels ran).
struct Sequence {
  std::size_t answer = 0;  // case index
  int levels = 0;          // usable levels
  int refined = 0;         // of which refined (level > 0)
  bool converged = false;
  FemErrors change;
  Measures limit;
  FemErrors limit_error;      // per metric, relative (the first contact: over the duration)
  Extrapolation peak;         // the peak force's extrapolation (order, observed), for cases.csv
  bool extrapolated = false;  // at least two refined levels
};

struct StudyCases {
  const StudyDef& def;
  std::vector<CaseData> cases;     // in plan_cases order
  std::vector<FemErrors> err_fem;  // per case, against the reference (below)
  // Per case: fem cases, (x − x_answer)/x_answer of the peak force against the answer of their
  // sequence (the discretization error); NaN for other models.
  std::vector<double> discretization_error;
  std::map<std::string, Sequence> sequences;  // particle|resolution|placement, fem only
  // The reference of each particle|placement, by the study's "reference":
  // - finest: the limit of the fem sequence at the finest resolution (its Richardson
  //   extrapolation; `index` the finest case of `cases`, whose curve the classification
  //   compares), and its uncertainty per metric, √(discretization² + geometry²): the
  //   extrapolation's estimated error, and the change of the limit from the next coarser
  //   resolution that was refined (is the finest geometry fine enough?).
  // - source: the particle itself (study/source_reference.hpp), the Richardson limit of the
  //   source reference's levels on the patch (`index` the finest of `source_cases`), and its
  //   uncertainty per metric, √(discretization² + patch²): the extrapolation's estimated error and
  //   the patch check's change (when run). No geometry term: the geometry is the particle's.
  //   The first contact is the finest level's (the free flight's), its last change the error.
  struct Reference {
    ReferenceKind kind = ReferenceKind::finest;
    std::size_t index = 0;
    long resolution = 0;           // the finest resolution's N (0: the source)
    long geometry_resolution = 0;  // the coarser N the geometry term compares with (0: none)
    int levels = 0;                // usable levels of its sequence, the coarse one included
    Extrapolation peak;            // the peak force's extrapolation (order, observed)
    // The source: per metric (kMetrics but the first contact) its extrapolation, and whether the
    // doubled patch ran.
    Extrapolation source_limit[3];
    bool patch_checked = false;
    // The source: the coarsest of the three levels the limit is from (1, or 2 where a fourth level
    // ran: source_reference.hpp, wants_finer_level), the finest level's size over the source's
    // R, and the CPU of every level of it (both patches), s.
    int limit_from = 0;
    double finest_size = std::nan(""), cpu = std::nan("");
    Measures values;
    FemErrors discretization, geometry, uncertainty;
    FemErrors patch;  // the source: the patch check's change per metric (signed; NaN: not run)
  };
  std::map<std::string, Reference> references;
  // The source reference's cases (plan_source_cases order): empty for "finest".
  std::vector<CaseData> source_cases;
  int done = 0, failed = 0;

  // The case, or nullptr when the study has none such.
  const CaseData* find(const std::string& particle, ModelKind m, long resolution, Placement pl,
                       int level = 0) const;
  const Sequence* sequence(const std::string& particle, long resolution, Placement pl) const;
  const Reference* reference(const std::string& particle, Placement pl) const;
  // The case whose force curve is the reference's (the finest level).
  const CaseData& reference_case(const Reference& r) const {
    return r.kind == ReferenceKind::source ? source_cases[r.index] : cases[r.index];
  }
  std::size_t index_of(const CaseData& c) const {
    return static_cast<std::size_t>(&c - cases.data());
  }
  std::size_t index_of_source(const CaseData& c) const {
    return static_cast<std::size_t>(&c - source_cases.data());
  }
  // A run that ended normally ("ok"): its measures can be compared.
  static bool usable(const CaseData* c) { return c && c->status == "ok"; }
  bool has_fem_reference() const;
  // Whether the study has a reference at all: the fem model ("finest") or the source.
  bool has_reference() const;

  std::map<std::string, std::size_t> index;  // particle|model|resolution|placement → case
};

// Reads DIR/cases/** and DIR/meshes/** for every planned case.
StudyCases load_study_cases(const StudyDef& def, const std::filesystem::path& dir);

// A force record (force.csv): time and force magnitude.
struct Curve {
  std::vector<double> t, f;
};
Curve read_force(const std::filesystem::path& file);

OJson num_or_null(const OJson& j, const char* key);
double rel_err(const OJson& v, const OJson& ref);
OJson finite_or_null(double x);
// A sphere case has no resolution: null.
OJson resolution_or_null(ModelKind m, long resolution);

// Writes FILE atomically: the header, then a row per entry, a field per JSON value. Numbers in
// the shortest form that reads back to the same double (as summary.json writes them), so a table
// and the case's summary.json hold the same value; null as an empty field.
void write_csv(const std::filesystem::path& file, const std::vector<std::string>& header,
               const std::vector<std::vector<OJson>>& rows);

}  // namespace asperity::study::tables
