// Stability sweep: measured against predicted critical steps (issue "Time-step stability").
#include "solver/run/stability_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <sstream>

#include "solver/core/error.hpp"
#include "solver/io/atomic_file.hpp"
#include "solver/io/csv.hpp"
#include "solver/run/run_scene.hpp"

namespace asperity::run {

std::vector<double> default_stability_factors() {
  return {0.05, 0.1, 0.25, 0.5, 0.75, 0.9, 1.0, 1.1, 1.25, 1.5, 2.0, 3.0, 5.0};
}

std::vector<double> parse_factors(const std::string& text, const std::string& what) {
  std::vector<double> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::size_t used = 0;
    double x = 0;
    try {
      x = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || !std::isfinite(x) || x <= 0) {
      throw InputError(what + ": \"" + item + "\" is not a positive number");
    }
    out.push_back(x);
  }
  if (out.empty()) throw InputError(what + ": empty list of factors");
  return out;
}

namespace {
double rel(double got, double ref) {
  return ref != 0 ? (got - ref) / std::abs(ref) : got - ref;
}
}  // namespace

StabilityResult stability_sweep(
    const scene::SceneDef& scene, std::vector<double> factors,
    std::optional<double> reference_factor,
    const std::function<void(const StabilityRow&, int, int)>& progress) {
  std::sort(factors.begin(), factors.end());
  factors.erase(std::unique(factors.begin(), factors.end()), factors.end());
  StabilityResult result;
  auto run_at = [&](std::optional<double> factor) {
    RunOptions o;
    o.dt_factor = factor;
    o.keep_rows = false;
    return run_scene(scene, o);
  };
  // The automatic step must be stable: run it (dt_factor empty) and read the safety factor the
  // model used (each model family has its own default when the scene gives none).
  std::string auto_status = "n/a (scene gives dt)";
  std::optional<double> safety = scene.dt_safety;
  double sweep_cpu = 0;
  int runs = 1;
  if (!scene.dt) {
    const RunResult automatic = run_at(std::nullopt);
    auto_status = automatic.status;
    sweep_cpu += automatic.summary["cpu_seconds"].get<double>();
    ++runs;
    safety = automatic.summary["dt_safety"].get<double>();
  }
  const double ref_factor =
      reference_factor.value_or(std::min(safety.value_or(1.0), factors.front() / 8));
  const RunResult ref = run_at(ref_factor);
  const double predicted = ref.summary["dt_critical_predicted"].get<double>();
  const double ref_peak = ref.summary["peak_force"].get<double>();
  const double ref_impulse = ref.summary["impulse"].get<double>();

  const int total = static_cast<int>(factors.size());
  for (int k = 0; k < total; ++k) {
    const RunResult r = run_at(factors[k]);
    StabilityRow row;
    row.factor = factors[k];
    row.dt = r.summary["dt"].get<double>();
    row.status = r.status;
    row.message = r.message;
    row.energy_drift = r.summary["energy_drift"].get<double>();
    row.peak_force = r.summary["peak_force"].get<double>();
    row.impulse = r.summary["impulse"].get<double>();
    row.cpu_seconds = r.summary["cpu_seconds"].get<double>();
    row.peak_force_error = rel(row.peak_force, ref_peak);
    row.impulse_error = rel(row.impulse, ref_impulse);
    result.rows.push_back(row);
    if (progress) progress(row, k + 1, total);
  }

  // Measured limit: the largest step below which every step tried stayed stable.
  std::optional<double> stable_max, first_unstable;
  sweep_cpu += ref.summary["cpu_seconds"].get<double>();
  for (const StabilityRow& row : result.rows) {
    sweep_cpu += row.cpu_seconds;
    if (row.status == "unstable") {
      if (!first_unstable) first_unstable = row.factor;
    } else if (!first_unstable) {
      stable_max = row.factor;
    }
  }
  auto& j = result.summary;
  j["scene"] = scene.name;
  j["dt_critical_predicted"] = predicted;
  j["dt_stable_max_measured"] =
      stable_max ? nlohmann::ordered_json(*stable_max * predicted) : nlohmann::ordered_json();
  j["stable_factor_max"] =
      stable_max ? nlohmann::ordered_json(*stable_max) : nlohmann::ordered_json();
  j["first_unstable_factor"] =
      first_unstable ? nlohmann::ordered_json(*first_unstable) : nlohmann::ordered_json();
  // Conservative prediction: ratio ≤ 1. The bracket is as fine as the factors tried.
  j["predicted_over_measured"] =
      stable_max ? nlohmann::ordered_json(1.0 / *stable_max) : nlohmann::ordered_json();
  j["status_at_largest_factor"] = result.rows.back().status;
  j["reference_factor"] = ref_factor;
  j["reference_status"] = ref.status;
  j["auto_status"] = auto_status;
  j["reference_peak_force"] = ref_peak;
  j["reference_impulse"] = ref_impulse;
  j["criteria"] =
      "unstable: non-finite state, total energy growth above unstable_energy_growth of "
      "the energy scale, a sphere overlap beyond the smaller radius (runaway overlap), a "
      "potential-contact penetration past half an element's centroid height or a body's centre "
      "inside another (runaway penetration), or an inverted tetrahedron";
  j["sweep_cpu_seconds"] = sweep_cpu;
  j["runs"] = result.rows.size() + static_cast<std::size_t>(runs);
  return result;
}

void write_stability(const StabilityResult& result, const std::filesystem::path& out) {
  std::filesystem::create_directories(out);
  io::CsvWriter csv({"factor", "dt", "status", "energy_drift", "peak_force", "cpu_seconds",
                     "impulse", "peak_force_error", "impulse_error"});
  for (const StabilityRow& r : result.rows) {
    csv.number(r.factor).number(r.dt).field(r.status).number(r.energy_drift);
    csv.number(r.peak_force).number(r.cpu_seconds).number(r.impulse);
    csv.number(r.peak_force_error).number(r.impulse_error).end_row();
  }
  io::write_atomically(out / "stability.csv", csv.str());
  io::write_atomically(out / "summary.json", result.summary.dump(2) + "\n");
}

}  // namespace asperity::run
