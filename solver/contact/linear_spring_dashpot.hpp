// Linear spring–dashpot normal contact (Cundall & Strack 1979), a pure function of one overlap.
#pragma once

#include <algorithm>
#include <cmath>

#include "solver/contact/hertz.hpp"

namespace asperity::contact {

struct LinearParams {
  double kn = 0;        // normal stiffness, N/m
  double mass_eff = 0;  // m*, kg
  double zeta = 0;      // dimensionless damping c/√(m* kn) (= 2 × damping ratio), from
                        // restitution_damping.hpp
};

// F = kn δ + ζ √(m* kn) δ̇, clipped at zero (no cohesion).
inline NormalForce linear_normal(double overlap, double overlap_rate, const LinearParams& p) {
  NormalForce out;
  out.elastic = p.kn * overlap;
  out.stiffness = p.kn;
  out.damping = p.zeta * std::sqrt(p.mass_eff * p.kn) * overlap_rate;
  out.force = std::max(0.0, out.elastic + out.damping);
  out.energy = 0.5 * p.kn * overlap * overlap;
  return out;
}

}  // namespace asperity::contact
