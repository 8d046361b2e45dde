// The one time-step policy of every runner (run/step_policy.hpp).
#include "solver/run/step_policy.hpp"

#include <cmath>

#include "solver/core/error.hpp"
#include "solver/core/format.hpp"

namespace asperity::run {

double default_safety(StepRegime regime) {
  switch (regime) {
    case StepRegime::spheres:
      return 0.01;
    case StepRegime::fdem_deformable:
      return 0.5;
    case StepRegime::fdem_rigid:
      return 0.1;
    case StepRegime::fdem_volume:
      return 0.01;
  }
  return 0.01;
}

StepChoice choose_step(const scene::SceneDef& s, const RunOptions& options, const StepPrediction& p,
                       StepRegime regime) {
  const std::string where = s.file.string() + ": ";
  StepChoice out;
  if (options.dt_factor) {
    if (!std::isfinite(p.critical)) {
      throw InputError(where + "dt: no predicted critical step to scale (no free body)");
    }
    out.dt = *options.dt_factor * p.critical;
  } else if (const std::optional<double> given = options.dt ? options.dt : s.dt) {
    out.dt = *given;
    if (out.dt > p.critical && !(options.allow_unsafe_dt || s.allow_unsafe_dt)) {
      throw InputError(where + "dt: " + fmt(out.dt) + " s exceeds the predicted critical step " +
                       fmt(p.critical) + " s (limited by " + p.limited_by +
                       "); use \"auto\", a smaller dt, or allow_unsafe_dt: true");
    }
  } else {
    if (!std::isfinite(p.critical)) {
      throw InputError(where +
                       "dt: \"auto\" has no critical step to scale (nothing moves); give dt in s");
    }
    out.automatic = true;
    out.safety = s.dt_safety.value_or(default_safety(regime));
    out.dt = out.safety * p.critical;
  }
  const std::string chosen = out.automatic ? "the auto step " : "";
  // A run of no full step, or with no step inside the shortest contact, measures nothing: it is
  // refused rather than reported as "no_contact" (in a sweep, reported unstable).
  std::string problem;
  if (!(out.dt > 0) || !std::isfinite(out.dt)) {
    problem = chosen + fmt(out.dt) + " s is not a positive finite step";
  } else if (out.dt > s.duration) {
    problem = chosen + fmt(out.dt) + " s is longer than the duration " + fmt(s.duration) +
              " s (the run would take no full step; check dt and the materials' density and young)";
  } else if (std::isfinite(p.shortest_contact) && p.shortest_contact > 0 &&
             out.dt > p.shortest_contact) {
    problem = chosen + fmt(out.dt) + " s is longer than the shortest predicted contact " +
              fmt(p.shortest_contact) + " s (fewer than one step per contact)";
  }
  if (!problem.empty()) {
    if (!options.dt_factor) throw InputError(where + "dt: " + problem);
    out.unresolved = "dt " + problem;
    return out;
  }
  const double n_steps = std::ceil(s.duration / out.dt - 1e-9);
  if (n_steps > 2e9) {
    throw InputError(where + "duration: " + fmt(s.duration) + " s needs " + fmt(n_steps) +
                     " steps of " + fmt(out.dt) + " s (over 2e9)");
  }
  out.steps = static_cast<long>(n_steps);
  return out;
}

}  // namespace asperity::run
