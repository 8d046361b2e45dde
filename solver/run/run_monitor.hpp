// What every model's time loop shares: the energy balance and its drift, the instability
// verdict, and the progress line. One policy for spheres and FEM/DEM alike.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "solver/core/energy.hpp"
#include "solver/core/format.hpp"

namespace asperity::run {

class RunMonitor {
 public:
  // growth_limit: the scene's unstable_energy_growth; n_steps for the progress line.
  RunMonitor(const std::string& name, const EnergyBalance& e0, double growth_limit, long n_steps,
             bool progress)
      : name_(name),
        e0_(e0),
        total0_(e0.total()),
        supplied_(e0.kinetic + e0.elastic + e0.contact),
        growth_limit_(growth_limit),
        n_steps_(n_steps),
        progress_(progress),
        wall0_(std::chrono::steady_clock::now()) {}

  // Feeds one energy evaluation at time t. The energy scale is what the physics supplied: the
  // initial kinetic, elastic and contact energy plus what gravity has released so far; growth
  // beyond it is made by the integrator. Flags a non-finite state or growth above the limit.
  void check_energy(double t, const EnergyBalance& e, bool state_finite) {
    supplied_ =
        std::max(supplied_, e0_.kinetic + e0_.elastic + e0_.contact + std::max(0.0, -e.gravity));
    if (!state_finite || !std::isfinite(e.total())) {
      flag("non-finite state at t = " + fmt(t) + " s");
      return;
    }
    if (supplied_ <= 0) return;
    const double growth = (e.total() - total0_) / supplied_;
    drift_ = std::max(drift_, std::abs(growth));
    if (growth > growth_limit_) {
      flag("energy grew by " + fmt(growth) + " of the energy supplied at t = " + fmt(t) + " s");
    }
  }

  // Records the first reason the run is unstable (later ones are consequences).
  void flag(const std::string& why) {
    if (unstable_.empty()) unstable_ = why;
  }

  bool unstable() const { return !unstable_.empty(); }
  const std::string& message() const { return unstable_; }
  double drift() const { return drift_; }
  std::string status(bool had_contact) const {
    return unstable() ? "unstable" : (had_contact ? "ok" : "no_contact");
  }

  // A progress line on stderr at most once a second, for runs longer than a second.
  void progress(long k) {
    if (!progress_ || (k & 255) != 0) return;
    const double el = elapsed();
    if (el - last_progress_ < 1.0) return;
    last_progress_ = el;
    const double done = static_cast<double>(k) / static_cast<double>(n_steps_);
    std::fprintf(stderr, "\r%s: %5.1f%%  step %ld/%ld  %.0f s left ", name_.c_str(), 100.0 * done,
                 k, n_steps_, el * (1 - done) / done);
  }
  void finish() const {
    if (progress_ && last_progress_ > 0) std::fprintf(stderr, "\n");
  }
  double elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0_).count();
  }

 private:
  std::string name_;
  EnergyBalance e0_;
  double total0_, supplied_, growth_limit_;
  long n_steps_;
  bool progress_;
  std::chrono::steady_clock::time_point wall0_;
  double drift_ = 0, last_progress_ = 0;
  std::string unstable_;
};

}  // namespace asperity::run
