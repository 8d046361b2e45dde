// Hertz normal contact force with Tsuji-form viscous damping (a pure function of one overlap).
#pragma once

#include <algorithm>
#include <cmath>

namespace asperity::contact {

// Parameters of one Hertz pair. K = 4/3 E* √R* (Johnson 1985, eq. 4.23: F = 4/3 E* √R* δ^{3/2}).
struct HertzParams {
  double young_eff = 0;   // E*, Pa
  double radius_eff = 0;  // R*, m (a plane or box counts as infinite radius: R* = the sphere's)
  double mass_eff = 0;    // m*, kg (a fixed body counts as infinite mass)
  double zeta = 0;        // dimensionless damping, from restitution_damping.hpp (0: elastic)
};

struct NormalForce {
  double force = 0;      // repulsive magnitude after clipping at zero (no cohesion), N
  double elastic = 0;    // elastic part 4/3 E* √R* δ^{3/2}, N
  double damping = 0;    // viscous part c·δ̇ (may be clipped in `force`), N
  double stiffness = 0;  // tangent stiffness dF/dδ = 2 E* a, N/m
  double energy = 0;     // stored elastic energy 8/15 E* √R* δ^{5/2}, J
};

inline double hertz_constant(const HertzParams& p) {
  return 4.0 / 3.0 * p.young_eff * std::sqrt(p.radius_eff);
}

// What of a Hertz pair does not change while it touches: K and the dashpot's ζ √(m* K). A world
// computes them once per pair of bodies, not per contact and step (dem/sphere_world.cpp).
struct HertzCoefficients {
  double k = 0;        // K = 4/3 E* √R*, N/m^{3/2}
  double damping = 0;  // ζ √(m* K), N·s/m^{5/4}
};

inline HertzCoefficients hertz_coefficients(const HertzParams& p) {
  const double k = hertz_constant(p);
  return {.k = k, .damping = p.zeta * std::sqrt(p.mass_eff * k)};
}

// overlap δ > 0 (m); overlap_rate δ̇ (m/s, positive while approaching).
// Damping F_d = ζ √(m* K) δ^{1/4} δ̇ (Tsuji et al. 1992 form: viscous force ∝ √(m* S_n) with
// the tangent stiffness S_n = 3/2 K δ^{1/2}). For this form the restitution depends on ζ only,
// not on the impact speed, so ζ(e) is computed once (restitution_damping.hpp). LIGGGHTS writes
// the same force as 2√(5/6) β √(S_n m*) δ̇, i.e. ζ = √5 β.
// The same with δ^{1/2} and δ^{1/4} given (Hertz–Mindlin takes its tangential stiffness and
// dashpot from them too, so each root is taken once per contact).
inline NormalForce hertz_normal(double overlap, double sqrt_overlap, double fourth_root_overlap,
                                double overlap_rate, const HertzCoefficients& c) {
  NormalForce out;
  out.elastic = c.k * overlap * sqrt_overlap;
  out.stiffness = 1.5 * c.k * sqrt_overlap;
  out.damping = c.damping * fourth_root_overlap * overlap_rate;
  out.force = std::max(0.0, out.elastic + out.damping);
  out.energy = 0.4 * out.elastic * overlap;
  return out;
}

inline NormalForce hertz_normal(double overlap, double overlap_rate, const HertzCoefficients& c) {
  const double sqrt_d = std::sqrt(overlap);
  return hertz_normal(overlap, sqrt_d, std::sqrt(sqrt_d), overlap_rate, c);
}

inline NormalForce hertz_normal(double overlap, double overlap_rate, const HertzParams& p) {
  return hertz_normal(overlap, overlap_rate, hertz_coefficients(p));
}

}  // namespace asperity::contact
