// The contract's summary.json core, written once for every runner and peer adapter: status and
// identity, the impact measures, the step, the run's length and cost. Each model adds its own
// keys after these (docs/contract.md, README "Outputs added to the contract").
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "solver/core/profile.hpp"
#include "solver/run/impact_measures.hpp"
#include "solver/run/step_policy.hpp"

namespace asperity::run {

using SummaryJson = nlohmann::ordered_json;

struct RunIdentity {
  std::string scene;          // the scene's name
  std::string model;          // "dem-spheres", "fdem", a peer's name
  std::string contact_law;    // the scene's law, as the scene names it
  std::string recorded_body;  // the body whose force is measured
};

// status, message (when unstable), scene, model, contact_law, recorded_body, peak_force,
// impulse, contact_duration (an open contact counts up to t_end), first_contact_time,
// max_overlap, restitution (null until the first contact ends), energy_drift (omitted when the
// producer cannot measure it, as for a peer).
void write_measures(SummaryJson& j, const RunIdentity& id, const std::string& status,
                    const std::string& message, const ImpactMeasures& im, double t_end,
                    std::optional<double> restitution, std::optional<double> energy_drift);

// dt, dt_critical_predicted, dt_limited_by, dt_safety (null for a given step).
void write_step(SummaryJson& j, const StepChoice& step, const StepPrediction& prediction);

// steps, simulated_time, ended_by ("separation" or "duration"), cpu_seconds, wall_seconds.
void write_run(SummaryJson& j, long steps, double simulated_time, bool ended_by_separation,
               double cpu_seconds, double wall_seconds);

// The profile in seconds from ticks (core/profile.hpp), given the run's seconds per tick;
// `internal` only for models with element forces.
SummaryJson profile_json(const Profile& p, double seconds_per_tick, bool internal);

// The result of a stability sweep's step that cannot resolve a contact (StepChoice::unresolved):
// unstable, not stepped, with the step keys written.
RunResult unresolved_run(const RunIdentity& id, const StepChoice& step,
                         const StepPrediction& prediction);

}  // namespace asperity::run
