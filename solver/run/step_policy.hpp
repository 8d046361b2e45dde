// The time-step policy every runner shares: which step a run takes ("auto" = dt_safety × the
// predicted critical step, a given dt checked against it, or a stability sweep's factor), and
// which runs are refused before they start. Written once here for spheres and FEM/DEM alike.
#pragma once

#include <optional>
#include <string>

#include "solver/run/run_result.hpp"
#include "solver/scene/scene.hpp"

namespace asperity::run {

// What a model predicts about its step (dem/time_step.hpp, fdem/time_step.hpp).
struct StepPrediction {
  double critical = 0;     // the predicted critical step, s (∞: nothing to size it)
  std::string limited_by;  // what sets it ("contact", "element", "rayleigh")
  // The shortest time a contact of this scene can last, s (∞ when unknown): a step longer
  // than it cannot resolve a single contact, whatever allow_unsafe_dt says.
  double shortest_contact = 0;
};

// The auto step's default safety factor per kind of scene (docs/physics.md, "Time step"):
// - spheres 0.01: ≥ 200 steps per Hertz contact keep the peak force within 1e-5 and the
//   energy error below 1e-4 (the analytic gates);
// - FEM/DEM with a deformable body 0.5: the step is set by element and penalty stiffness, a
//   contact spans thousands of steps at the critical one, and the bound is already conservative
//   (element eigenvalue and Gershgorin bounds);
// - rigid-only mesh scenes 0.1: the rigid bound over the pressed patch is sharp, so 0.5 of it
//   resolves a contact in 10–15 steps only; the peak force was 0.4–0.8 % off the converged-step
//   value on three study particles at 250 and 1000 triangles, 0.02–0.06 % at 0.1.
// - rigid polyhedra under a volume law 0.01: the step is 2/ω of the Hertz-equivalent pair at its
//   peak (or of a flat face's approach, fdem/time_step.cpp), about half the contact, as for
//   spheres: restitution 1 within 1e-4 and energy drift below 1e-4 for faceted spheres and a
//   cube's vertex, edge and face (tests/fdem/test_volume_contact.cpp).
enum class StepRegime { spheres, fdem_deformable, fdem_rigid, fdem_volume };
double default_safety(StepRegime regime);

struct StepChoice {
  double dt = 0;   // s
  long steps = 0;  // ceil(duration / dt)
  bool automatic = false;
  double safety = 0;  // the dt_safety used when automatic
  // A stability sweep's step (RunOptions::dt_factor) that takes no full step or none inside the
  // shortest contact: not an input error there but a run that cannot be stable; the runner
  // reports it unstable with this message without stepping.
  std::string unresolved;
};

// Chooses the step. Throws InputError (file: key: problem) for a given dt above the critical
// step without allow_unsafe_dt, for "auto" with nothing to size it, for a step longer than the
// duration or than the shortest contact (a run of no full step, or of no step inside a contact,
// measures nothing; a sweep's factor gets StepChoice::unresolved instead), and for more than 2e9
// steps.
StepChoice choose_step(const scene::SceneDef& scene, const RunOptions& options,
                       const StepPrediction& prediction, StepRegime regime);

}  // namespace asperity::run
