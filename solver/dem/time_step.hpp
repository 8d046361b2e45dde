// Predicted critical time step for rigid spheres, formulas and sources beside the code.
#pragma once

#include <string>

#include "solver/dem/sphere_world.hpp"

namespace asperity::dem {

struct CriticalStep {
  double rayleigh = 0;            // Rayleigh-wave step, s (reported; see below)
  double contact = 0;             // stability limit of the stiffest contact oscillation, s
  double hertz_contact_time = 0;  // Hertz duration at the largest approach speed, s (reference)
  double approach_speed = 0;      // the largest approach speed assumed, m/s
  double critical = 0;            // the predicted critical step, s
  std::string limited_by;         // "contact", or "rayleigh" when no contact can be sized
};

// Contact step: central differences are stable for ω dt < 2; with damping ratio ξ the bound is
// (2/ω)(√(1+ξ²) − ξ) (Belytschko, Liu & Moran 2000, §6.2). For Hertz the stiffest moment is the
// peak overlap δ_max at the largest approach speed v, where dF/dδ = 3/2 K δ_max^{1/2}; that step
// is about half the Hertz contact time 2.94 δ_max / v. The worst pair is bounded by the smallest
// m* (half the lightest sphere's mass), the largest R* and the largest E* in the scene; v is
// twice the fastest sphere (plus radius × spin) plus the fall √(2|g|H) over the scene's height
// H along gravity. The linear law uses k = kn: dt = 2 √(m*/kn), corrected for damping.
// This is the predicted critical step: rigid spheres carry no elastic waves, so the contact
// oscillator is what central differences must resolve. The Rayleigh step
// dt_R = π r √(ρ/G) / (0.1631 ν + 0.8766) (Li, Xu & Thornton 2005), the usual heuristic for dense
// packings, is reported beside it and used only when no contact can be sized (no motion).
CriticalStep critical_step(const SphereWorld& world);

}  // namespace asperity::dem
