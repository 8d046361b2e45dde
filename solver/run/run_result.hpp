// What a run produces, whichever model ran it: the rows of force.csv and energy.csv and the
// summary.json object (run/summary.hpp writes its core), and the options a caller may set.
#pragma once

#include <chrono>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/run/vtk_output.hpp"

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
  // A wall-clock deadline (a caller's budget, `advise --budget`, `study --stop-after`): the time
  // loop looks at the clock every 256 steps and, once past it, throws RunStopped. A run so
  // stopped has no result: the budget, not the physics, ended it, so nothing may be written.
  std::optional<std::chrono::steady_clock::time_point> stop_at;
};

// Thrown by the time loop at RunOptions::stop_at: the run was cut short by its caller's budget.
class RunStopped : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RunResult {
  std::string status;   // "ok", "unstable" or "no_contact"
  std::string message;  // why, when unstable
  nlohmann::ordered_json summary;
  std::vector<ForceRow> force;
  std::vector<EnergyRow> energy;
  SeriesStats vtk;  // frames written (not in the summary: frames change no result)
};

}  // namespace asperity::run
