// The one time loop of every model (spheres, FEM/DEM): step → contact output → impact measures
// → energy check → rows → progress, until the duration, an instability, or the recorded body's
// separation. A model plugs in through a small adapter (run_spheres.cpp, run_fdem.cpp) with:
//   void prepare(bool energy_wanted)   before the step (FEM/DEM computes energy integrals only
//                                      when asked)
//   void step(double dt)
//   std::string failure()              after the step: why it went unstable, or empty
//   const BodyContacts& contacts()     this step's contact output (core/body_contacts.hpp)
//   Vec3 relative_velocity()           recorded body's centre relative to its partner's
//   EnergyBalance energy(); bool finite(); double time(); long check_every()
//   int record                         the recorded body's index in contacts()
// An observer (ParaView frames, run/vtk_series.hpp) is called after every completed step; it only
// reads the model, so it changes no result. run_model wraps the loop in what every runner does
// around it (frames, status, the summary's core), so a runner adds only its model's keys.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "solver/core/body_contacts.hpp"
#include "solver/core/clock.hpp"
#include "solver/core/energy.hpp"
#include "solver/core/ticks.hpp"
#include "solver/run/impact_measures.hpp"
#include "solver/run/run_monitor.hpp"
#include "solver/run/run_scene.hpp"
#include "solver/run/step_policy.hpp"
#include "solver/run/summary.hpp"
#include "solver/scene/scene.hpp"

namespace asperity::run {

// After step k: the recorded body's contact force magnitude (N), and whether the run ends there.
using StepObserver = std::function<void(long k, double force, bool last)>;

struct LoopOutcome {
  ImpactMeasures impact;
  Restitution restitution;
  std::string status, message;
  double energy_drift = 0;
  bool ended_by_separation = false;
  double cpu_seconds = 0, wall_seconds = 0;
  // The loop's wall time over its tick count (core/ticks.hpp): turns the profile's ticks into
  // seconds.
  double seconds_per_tick = 0;
};

template <class Model>
LoopOutcome time_loop(Model& m, const scene::SceneDef& s, const RunOptions& options,
                      const StepChoice& step, RunResult& result,
                      const StepObserver& observer = {}) {
  LoopOutcome out;
  const auto wall0 = std::chrono::steady_clock::now();
  const double cpu0 = thread_cpu_seconds();
  const std::uint64_t ticks0 = ticks();
  const int rec = m.record;
  auto sample_force = [&] { return Vec3(m.contacts().force.col(rec)); };
  auto sample_overlap = [&] { return m.contacts().overlap[static_cast<std::size_t>(rec)]; };
  out.impact.start(m.time(), sample_force(), sample_overlap());
  const EnergyBalance e0 = m.energy();
  RunMonitor monitor(s.name, e0, s.unstable_energy_growth, step.steps, options.progress);
  auto push_rows = [&](const EnergyBalance& e) {
    if (!options.keep_rows) return;
    const Vec3 f = sample_force();
    result.force.push_back({m.time(), f.x(), f.y(), f.z(), f.norm()});
    result.energy.push_back(
        {m.time(), e.kinetic, e.elastic, e.contact, e.gravity, e.dissipated, e.total()});
  };
  push_rows(e0);
  const long check_every = m.check_every();
  const int every = std::max(1, s.record.every);
  for (long k = 1; k <= step.steps && !monitor.unstable(); ++k) {
    const bool row_due = k % every == 0 || k == step.steps;
    m.prepare(row_due || k % check_every == 0);
    const bool touching_before = out.impact.touching;
    const Vec3 v_before = m.relative_velocity();
    m.step(step.dt);
    if (const std::string why = m.failure(); !why.empty()) {
      monitor.flag(why);
      break;
    }
    out.impact.add(m.time(), sample_force(), sample_overlap());
    out.restitution.add(touching_before, out.impact.touching, v_before, m.relative_velocity(),
                        m.contacts().normal_force.col(rec), step.dt);
    out.ended_by_separation = s.record.end_after_separation &&
                              out.impact.separated_for(m.time(), *s.record.end_after_separation);
    // Energy is checked where the model computed it (prepare's flag); a row written only
    // because the run stops at separation carries the model's latest energies unchecked.
    if (row_due || k % check_every == 0) {
      const EnergyBalance e = m.energy();
      monitor.check_energy(m.time(), e, m.finite());
      if (row_due) push_rows(e);
    }
    if (out.ended_by_separation && !row_due) push_rows(m.energy());
    if (observer) observer(k, sample_force().norm(), k == step.steps || out.ended_by_separation);
    monitor.progress(k);
    if (out.ended_by_separation) break;
    if (options.stop_at && (k & 255) == 0 && std::chrono::steady_clock::now() >= *options.stop_at) {
      monitor.finish();
      throw RunStopped("stopped at step " + std::to_string(k) + " of " +
                       std::to_string(step.steps) + ": the budget ran out");
    }
  }
  monitor.finish();
  const std::uint64_t tick_count = ticks() - ticks0;
  out.cpu_seconds = thread_cpu_seconds() - cpu0;
  out.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  out.seconds_per_tick = seconds_per_tick(out.wall_seconds, tick_count);
  out.status = monitor.status(out.impact.first_contact_time >= 0);
  out.message = monitor.message();
  out.energy_drift = monitor.drift();
  return out;
}

// The loop with what every runner does around it, written once: the ParaView frames (`frames`,
// empty when none were asked for) observe every step and are finished after the last, the
// status is copied into the result, and the summary's core (run/summary.hpp: status, identity,
// impact measures, restitution, energy drift) is written. The model's own keys follow.
template <class Model, class Series>
LoopOutcome run_model(Model& m, std::optional<Series>& frames, const RunIdentity& id,
                      const scene::SceneDef& s, const RunOptions& options, const StepChoice& step,
                      RunResult& result) {
  StepObserver observer;
  if (frames) {
    observer = [&](long k, double force, bool last) { frames->after_step(m.w, k, force, last); };
  }
  const LoopOutcome loop = time_loop(m, s, options, step, result, observer);
  if (frames) {
    frames->finish(m.w);
    result.vtk = frames->stats();
  }
  result.status = loop.status;
  result.message = loop.message;
  write_measures(result.summary, id, loop.status, loop.message, loop.impact, m.time(),
                 loop.restitution.value(), loop.energy_drift);
  return loop;
}

}  // namespace asperity::run
