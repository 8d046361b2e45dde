// The contract's summary core (run/summary.hpp).
#include "solver/run/summary.hpp"

namespace asperity::run {

namespace {
SummaryJson optional_json(std::optional<double> x) {
  return x ? SummaryJson(*x) : SummaryJson();
}
}  // namespace

void write_measures(SummaryJson& j, const RunIdentity& id, const std::string& status,
                    const std::string& message, const ImpactMeasures& im, double t_end,
                    std::optional<double> restitution, std::optional<double> energy_drift) {
  j["status"] = status;
  if (!message.empty()) j["message"] = message;
  j["scene"] = id.scene;
  j["model"] = id.model;
  j["contact_law"] = id.contact_law;
  j["recorded_body"] = id.recorded_body;
  j["peak_force"] = im.peak_force;
  j["impulse"] = im.impulse;
  j["contact_duration"] = im.duration_until(t_end);
  j["first_contact_time"] =
      im.first_contact_time < 0 ? SummaryJson() : SummaryJson(im.first_contact_time);
  j["max_overlap"] = im.max_overlap;
  j["restitution"] = optional_json(restitution);
  if (energy_drift) j["energy_drift"] = *energy_drift;
}

void write_step(SummaryJson& j, const StepChoice& step, const StepPrediction& prediction) {
  j["dt"] = step.dt;
  j["dt_critical_predicted"] = prediction.critical;
  j["dt_limited_by"] = prediction.limited_by;
  j["dt_safety"] = step.automatic ? SummaryJson(step.safety) : SummaryJson();
}

void write_run(SummaryJson& j, long steps, double simulated_time, bool ended_by_separation,
               double cpu_seconds, double wall_seconds) {
  j["steps"] = steps;
  j["simulated_time"] = simulated_time;
  j["ended_by"] = ended_by_separation ? "separation" : "duration";
  j["cpu_seconds"] = cpu_seconds;
  j["wall_seconds"] = wall_seconds;
}

SummaryJson profile_json(const Profile& p, double per_tick, bool internal) {
  auto s = [&](std::uint64_t t) { return per_tick * static_cast<double>(t); };
  SummaryJson j = {{"broad_phase", s(p.broad_phase)}, {"contact", s(p.contact)}};
  if (internal) j["internal_forces"] = s(p.internal);
  j["integrate"] = s(p.integrate);
  return j;
}

RunResult unresolved_run(const RunIdentity& id, const StepChoice& step,
                         const StepPrediction& prediction) {
  RunResult r;
  r.status = "unstable";
  r.message = step.unresolved;
  write_measures(r.summary, id, r.status, r.message, ImpactMeasures{}, 0, std::nullopt, 0.0);
  write_step(r.summary, step, prediction);
  write_run(r.summary, 0, 0, false, 0, 0);
  return r;
}

}  // namespace asperity::run
