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

// |F_peak| and impulse of a case relative to the fem reference of its particle and placement;
// NaN where either is not usable.
struct FemErrors {
  double peak = std::nan(""), impulse = std::nan("");
};

struct StudyCases {
  const StudyDef& def;
  std::vector<CaseData> cases;     // in plan_cases order
  std::vector<FemErrors> err_fem;  // per case
  int done = 0, failed = 0;

  // The case, or nullptr when the study has none such.
  const CaseData* find(const std::string& particle, ModelKind m, long resolution,
                       Placement pl) const;
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
