// Stability of the explicit central-difference (velocity Verlet) step, the one integrator of
// every model here.
#pragma once

#include <cmath>
#include <limits>

namespace asperity {

// Critical step of an oscillator of angular frequency ω (rad/s) and damping ratio ξ: undamped
// central differences are stable for ω dt < 2, and with viscous damping the bound tightens to
// dt = (2/ω)(√(1+ξ²) − ξ) (Belytschko, Liu & Moran 2000, Nonlinear Finite Elements, §6.2).
// ∞ when ω = 0 (nothing to resolve).
inline double damped_critical_step(double omega, double xi) {
  if (!(omega > 0)) return std::numeric_limits<double>::infinity();
  return 2.0 / omega * (std::sqrt(1 + xi * xi) - xi);
}

}  // namespace asperity
