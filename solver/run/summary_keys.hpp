// Every top-level key of a summary.json, by what writes it: a run (the summary core,
// run/summary.hpp, and each model's keys: run_spheres.cpp, run_fdem.cpp, rebound.cpp) and a
// stability sweep (run/stability_sweep.cpp). docs/scenes.md documents exactly these, in its
// "`summary.json`" tables (tests/scene/test_scene_keys.cpp holds the two to each other, and
// tests/examples/run_examples.sh each example's summary to the doc); a validation case may check
// any scalar key (validation/case.cpp), so a misspelt quantity is bad input before anything runs.
#pragma once

#include <string_view>
#include <vector>

namespace asperity::run::summary_keys {

// A run's keys whose value is a number, a string or null.
inline constexpr std::string_view kRun[] = {
    "status", "message", "scene", "model", "contact_law", "recorded_body",
    // impact measures (run/impact_measures.hpp)
    "peak_force", "impulse", "contact_duration", "first_contact_time", "max_overlap",
    "max_penetration_ratio", "peak_force_filtered", "ringing_amplitude", "restitution",
    "energy_drift",
    // oblique rebound (run/rebound.hpp)
    "impact_partner", "normal_velocity_in", "normal_velocity_out", "tangential_velocity_in",
    "tangential_velocity_out", "slip_velocity_in", "slip_velocity_out", "spin_in", "spin_out",
    "tangential_restitution", "slip_ratio", "incident_angle_deg", "rebound_angle_deg",
    "angular_velocity_change", "tangential_speed_out", "final_speed", "final_spin",
    // the step (run/step_policy.hpp) and the model's bounds
    "dt", "dt_critical_predicted", "dt_rayleigh", "dt_element", "dt_contact", "dt_limited_by",
    "dt_safety", "assumed_approach_speed",
    // the contact's parameters as used
    "penalty", "penalty_alpha", "penalty_alpha_asked", "max_contact_factor", "penalty_scale_min",
    "added_mass_fraction", "kv", "friction",
    // the deformable recorded body's elastic law
    "material_law",
    // the run's length and cost
    "steps", "simulated_time", "ended_by", "cpu_seconds", "wall_seconds", "neighbour_rebuilds",
    "contact_updates", "contact_evaluations", "contacts_touching", "surface_tets", "state_bytes"};

// A run's keys whose value is an array or an object: documented, not checkable as one value.
inline constexpr std::string_view kRunStructured[] = {"final_velocity", "final_angular_velocity",
                                                      "profile", "damping", "bodies"};

// A stability sweep's keys (all scalar).
inline constexpr std::string_view kSweep[] = {"scene",
                                              "dt_critical_predicted",
                                              "dt_stable_max_measured",
                                              "stable_factor_max",
                                              "first_unstable_factor",
                                              "predicted_over_measured",
                                              "status_at_largest_factor",
                                              "reference_factor",
                                              "reference_status",
                                              "auto_status",
                                              "reference_peak_force",
                                              "reference_impulse",
                                              "criteria",
                                              "sweep_cpu_seconds",
                                              "runs"};

// What a validation case may check: every scalar key of a run or a sweep.
inline std::vector<std::string_view> checkable() {
  std::vector<std::string_view> out(std::begin(kRun), std::end(kRun));
  out.insert(out.end(), std::begin(kSweep), std::end(kSweep));
  return out;
}

}  // namespace asperity::run::summary_keys
