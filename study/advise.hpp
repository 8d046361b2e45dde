// `asperity advise MESH`: a user's own particle studied at K orientations, each against its own
// reference, and the cheapest model, resolution and element size within a tolerance
// (docs/study.md, "Advice on a particle").
#pragma once

#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "study/study_def.hpp"
#include "study/tables/study_cases.hpp"

namespace asperity::study {

struct AdviseOptions {
  std::filesystem::path mesh;
  double scale = 1;                   // multiplies the file's coordinates (0.001 for millimetres)
  int orientations = 4;               // K random orientations
  std::string metric = "peak_force";  // peak_force, impulse or contact_duration
  double tolerance = 0.05;            // relative
};

// The study advise runs: `template_file` (data/study/advise.json: the models, resolutions and
// refinement) with MESH as its one particle at K orientations, written as DIR/advise_study.json
// and read back like any study file (so its checks and folder layout are the study's).
StudyDef write_advice_study(const std::filesystem::path& template_file, const AdviseOptions& o,
                            const std::filesystem::path& out);

// One candidate (model, resolution, element size) over the orientations done: |error| against
// each orientation's reference in one metric, median and worst, and its median CPU per impact.
struct AdviceCandidate {
  ModelKind model = ModelKind::fem;
  long resolution = 0;       // 0 for a sphere
  int level = 0;             // fem: 0 coarse, k the k-th refined element size
  double relative_size = 0;  // that size over the equivalent radius
  int orientations = 0;
  double error_median = std::nan(""), error_worst = std::nan(""), cpu = std::nan("");
};
// Every candidate with an error at every orientation that has a reference.
std::vector<AdviceCandidate> advice_candidates(const tables::StudyCases& s,
                                               const std::string& metric);

// The advice for one metric and tolerance: the cheapest candidate whose worst orientation is
// within the tolerance (`met`), or else the one with the smallest worst error; the reference's
// uncertainty (median and worst over the orientations) beside it.
struct Advice {
  std::string metric;
  double tolerance = 0;
  bool met = false;
  AdviceCandidate pick;  // model none (orientations 0) when no candidate has the metric
  double reference_uncertainty_median = std::nan(""), reference_uncertainty_worst = std::nan("");
};
Advice advise(const std::vector<AdviceCandidate>& candidates, const std::string& metric,
              double tolerance, std::pair<double, double> reference_uncertainty);

// The reference's uncertainty in `metric` over the orientations: (median, worst).
std::pair<double, double> reference_uncertainty_over(const tables::StudyCases& s,
                                                     const std::string& metric);

// advice.json and advice.md in DIR: the advice asked for, and the same for every metric and every
// tolerance of the study's answer (2, 5, 10 %). `run` adds the run's facts (orientations asked
// and done, CPU, wall). Returns advice.json.
nlohmann::ordered_json write_advice(const tables::StudyCases& s, const AdviseOptions& o,
                                    const nlohmann::ordered_json& run,
                                    const std::filesystem::path& dir);

}  // namespace asperity::study
