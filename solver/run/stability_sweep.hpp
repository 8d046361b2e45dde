// Time-step stability sweep: a scene run at multiples of its predicted critical step.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/scene/scene.hpp"

namespace asperity::run {

struct StabilityRow {
  double factor = 0, dt = 0;
  std::string status;  // run status: ok, no_contact or unstable
  std::string message;
  double energy_drift = 0, peak_force = 0, impulse = 0, cpu_seconds = 0;
  double peak_force_error = 0, impulse_error = 0;  // relative to the reference run
};

struct StabilityResult {
  std::vector<StabilityRow> rows;  // ascending factor
  nlohmann::ordered_json summary;
};

// Default factors: dense around the limit, a few far past it.
std::vector<double> default_stability_factors();

// Parses "0.1,0.5,1" (CLI). Throws InputError naming `what` for an empty list or a factor that
// is not a positive finite number.
std::vector<double> parse_factors(const std::string& text, const std::string& what);

// Runs the scene at each factor × dt_critical_predicted (unstable runs stop early) plus a
// reference at reference_factor (default: the smaller of the dt_safety the automatic step used and
// an eighth of the smallest factor), and classifies each run. `progress` is called after each run.
StabilityResult stability_sweep(
    const scene::SceneDef& scene, std::vector<double> factors,
    std::optional<double> reference_factor = std::nullopt,
    const std::function<void(const StabilityRow&, int, int)>& progress = {});

// DIR/stability.csv and DIR/summary.json (each via a temporary file and a rename).
void write_stability(const StabilityResult& result, const std::filesystem::path& out);

}  // namespace asperity::run
