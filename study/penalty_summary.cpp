// penalty_summary PENALTY.csv SUMMARY.csv: the summary of the penalty-sensitivity runs
// (tools/report/penalty_sensitivity.sh; reports/study/penalty/), one row per penalty α, computed
// here so the Markdown of penalty_sensitivity.py and the study report's penalty section only read
// it. PENALTY.csv is the per-case table penalty_sensitivity.py writes (particle, model,
// resolution, alpha, cpu_seconds and the changes peak_vs_finest, peak_vs_stiffest,
// impulse_vs_stiffest); SUMMARY.csv has, over the fem cases at that α:
// - peak_vs_finest_median: the median |peak − peak at the finest mesh| / that, coarser meshes only;
// - peak_vs_stiffest_median, impulse_vs_stiffest_median: the median |change| from the stiffest α;
// - cpu_seconds_finest_mean: the mean CPU seconds at the finest mesh.
// Medians are the one quantile (solver/core/quantile.hpp, type 7) over the finite changes (a case
// without its finest or stiffest partner has none); numbers to the last bit (17 digits), so a
// reader formats exactly these doubles. Bad input: one line naming the file and the problem,
// exit 2.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "solver/core/quantile.hpp"
#include "solver/io/atomic_file.hpp"
#include "solver/io/csv.hpp"

namespace {

struct Row {
  std::string model;
  long resolution = 0;
  double alpha = 0, cpu_seconds = 0, peak_vs_finest = 0, peak_vs_stiffest = 0,
         impulse_vs_stiffest = 0;
};

// The rows of PENALTY.csv (plain fields: penalty_sensitivity.py writes no quoted ones).
std::vector<Row> read_rows(const std::string& file) {
  const asperity::io::CsvTable t = asperity::io::read_csv_table(file);
  const std::size_t model = t.required("model"), resolution = t.required("resolution"),
                    alpha = t.required("alpha"), cpu = t.required("cpu_seconds"),
                    finest = t.required("peak_vs_finest"),
                    stiffest = t.required("peak_vs_stiffest"),
                    impulse = t.required("impulse_vs_stiffest");
  std::vector<Row> rows;
  for (std::size_t k = 0; k < t.rows.size(); ++k) {
    rows.push_back({.model = model < t.rows[k].size() ? t.rows[k][model] : "",
                    .resolution = std::lround(t.number(k, resolution)),
                    .alpha = t.number(k, alpha),
                    .cpu_seconds = t.number(k, cpu),
                    .peak_vs_finest = t.number(k, finest),
                    .peak_vs_stiffest = t.number(k, stiffest),
                    .impulse_vs_stiffest = t.number(k, impulse)});
  }
  if (rows.empty()) throw asperity::InputError("has no cases");
  return rows;
}

std::string summary(const std::vector<Row>& rows) {
  long finest = 0;
  for (const Row& r : rows) finest = std::max(finest, r.resolution);
  std::map<double, std::vector<const Row*>> fem;  // by α, ascending
  for (const Row& r : rows) {
    auto& at = fem[r.alpha];  // every α a row, fem cases or none
    if (r.model == "fem") at.push_back(&r);
  }
  const auto median = [](const std::vector<const Row*>& at, auto change, auto keep) {
    std::vector<double> v;
    for (const Row* r : at) {
      if (keep(*r) && std::isfinite(change(*r))) v.push_back(std::abs(change(*r)));
    }
    return asperity::quantile(v, 0.5);
  };
  const auto all = [](const Row&) { return true; };
  asperity::io::CsvWriter csv(
      {"alpha", "finest_resolution", "peak_vs_finest_median", "peak_vs_stiffest_median",
       "impulse_vs_stiffest_median", "cpu_seconds_finest_mean"},
      17);
  for (const auto& [alpha, at] : fem) {
    double cpu = 0;
    long cases = 0;
    for (const Row* r : at) {
      if (r->resolution != finest) continue;
      cpu += r->cpu_seconds;
      ++cases;
    }
    csv.number(alpha)
        .number(static_cast<double>(finest))
        .number(median(
            at, [](const Row& r) { return r.peak_vs_finest; },
            [&](const Row& r) { return r.resolution != finest; }))
        .number(median(
            at, [](const Row& r) { return r.peak_vs_stiffest; }, all))
        .number(median(
            at, [](const Row& r) { return r.impulse_vs_stiffest; }, all))
        .number(cpu / static_cast<double>(std::max(1L, cases)))
        .end_row();
  }
  return csv.str();
}

}  // namespace

int main(int argc, char** argv) {
  return asperity::io::table_program(argc, argv, 2, "penalty_summary PENALTY.csv SUMMARY.csv", [&] {
    asperity::io::write_atomically(argv[2], summary(read_rows(argv[1])));
  });
}
