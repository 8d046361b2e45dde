// Predicted critical time step for rigid spheres (issue: "Time step"), formulas beside the code.
#pragma once

#include <string>

#include "dem/sphere_world.hpp"

namespace asperity::dem {

struct CriticalStep {
  double rayleigh = 0;     // Rayleigh-wave step, s
  double contact = 0;      // stability limit of the stiffest contact oscillation, s
  double hertz_contact_time = 0;  // Hertz duration at the largest approach speed, s (for reference)
  double approach_speed = 0;      // the largest approach speed assumed, m/s
  double critical = 0;     // min(rayleigh, contact), s
  std::string limited_by;  // "rayleigh" or "contact"
};

// Rayleigh step dt_R = π r √(ρ/G) / (0.1631 ν + 0.8766) (Li et al. 2005; Thornton 2015, §2.4),
// smallest over the free spheres.
// Contact step: central differences are stable for ω dt < 2; with damping ratio ξ the bound is
// (2/ω)(√(1+ξ²) − ξ) (Belytschko et al. 2000, eq. 6.2.23). For Hertz the stiffest moment is the
// peak overlap δ_max at the largest approach speed v, where dF/dδ = 3/2 K δ_max^{1/2}; that step
// is about half the Hertz contact time 2.94 δ_max / v. The worst pair is bounded by the smallest
// m* (half the lightest sphere's mass), the largest R* and the largest E* in the scene; v is
// twice the fastest sphere plus the fall √(2|g|H) over the scene's height H along gravity.
// The linear law uses k = kn: dt = 2 √(m*/kn) corrected for damping.
CriticalStep critical_step(const SphereWorld& world);

}  // namespace asperity::dem
