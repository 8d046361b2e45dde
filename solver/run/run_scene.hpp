// Runs one scene to its end and measures what the contract's summary.json reports.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "run/vtk_series.hpp"
#include "scene/scene.hpp"

namespace asperity::run {

struct ForceRow {
  double t, fx, fy, fz, f;
};
struct EnergyRow {
  double t, kinetic, elastic, contact, gravity, dissipated, total;
};

struct RunOptions {
  std::optional<double> dt;         // overrides the scene's dt
  std::optional<double> dt_factor;  // dt = factor × the predicted critical step (stability
                                    // sweeps; implies allow_unsafe_dt); wins over `dt`
  bool allow_unsafe_dt = false;
  bool keep_rows = true;  // fill force and energy rows (off for sweeps)
  bool progress = false;  // progress line on stderr for long runs
  // ParaView frames (run/vtk_series.hpp); none unless set with every > 0.
  std::optional<VtkOutput> vtk;
};

struct RunResult {
  std::string status;   // "ok", "unstable" or "no_contact"
  std::string message;  // why, when unstable
  nlohmann::ordered_json summary;
  std::vector<ForceRow> force;
  std::vector<EnergyRow> energy;
  SeriesStats vtk;  // frames written (not in the summary: frames change no result)
};

// Throws InputError for a scene the solver cannot run (bad geometry, unsafe dt, ...).
RunResult run_scene(const scene::SceneDef& scene, const RunOptions& options = {});

// Writes summary.json, force.csv and energy.csv into `out` (each via a temporary file and a
// rename, summary.json last); an unstable run writes summary.json only.
void write_outputs(const RunResult& result, const std::filesystem::path& out);

}  // namespace asperity::run
