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

#include "study/study_def.hpp"
#include "study/study_run.hpp"

namespace asperity::study::tables {

using OJson = nlohmann::ordered_json;

struct CaseData {
  CaseKey key;
  std::string status;  // "ok", "unstable", "no_contact", "failed", "missing"
  std::string message;
  OJson summary, mesh;
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

// The fem refinement sequence of one (particle, resolution, placement): its answer (the finest
// usable level; the coarse case when the study refines none), whether the last refinement moved
// the peak force by less than the study's tolerance, and per metric the change between the two
// finest levels, the answer's estimated discretization error (NaN with a single level).
struct Sequence {
  std::size_t answer = 0;  // case index
  int levels = 0;          // usable levels
  bool converged = false;
  FemErrors change;
};

struct StudyCases {
  const StudyDef& def;
  std::vector<CaseData> cases;     // in plan_cases order
  std::vector<FemErrors> err_fem;  // per case, against the reference (below)
  // Per case: fem cases, (x − x_answer)/x_answer of the peak force against the answer of their
  // sequence (the discretization error); NaN for other models.
  std::vector<double> discretization_error;
  std::map<std::string, Sequence> sequences;  // particle|resolution|placement, fem only
  // The reference of each particle|placement: the fem answer at the finest resolution, and its
  // uncertainty per metric, √(discretization² + geometry²): the change of its own sequence's
  // last refinement, and the change of the converged answer from the next coarser resolution
  // (is the finest geometry fine enough?).
  struct Reference {
    std::size_t index = 0;
    FemErrors discretization, geometry, uncertainty;
  };
  std::map<std::string, Reference> references;
  int done = 0, failed = 0;

  // The case, or nullptr when the study has none such.
  const CaseData* find(const std::string& particle, ModelKind m, long resolution, Placement pl,
                       int level = 0) const;
  const Sequence* sequence(const std::string& particle, long resolution, Placement pl) const;
  const Reference* reference(const std::string& particle, Placement pl) const;
  std::size_t index_of(const CaseData& c) const {
    return static_cast<std::size_t>(&c - cases.data());
  }
  // A run that ended normally ("ok"): its measures can be compared.
  static bool usable(const CaseData* c) { return c && c->status == "ok"; }
  bool has_fem_reference() const;

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
