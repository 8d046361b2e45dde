// Volume-Hertz: an elastic contact energy of the overlap volume alone, W(V) = c V^{5/4}, scaled so
// that two smooth spheres (or a sphere and a plane) obey Hertz (docs/physics.md, "Volume laws").
//
// With the overlap geometry of contact/overlap_volume.hpp the force on body A is
// F_A = −W'(V) S_A (S_A the area vector of A's surface inside B) and its torque about its centre
// −W'(V) M_A: the exact gradient of W, so an impact is elastic (restitution 1) whatever the shape
// (Feng 2021, CMAME 373, 113454, §3: any W(V) of the contact volume alone is energy-conserving).
//
// The scale. A sphere of radius R pressed δ into a plane: V = π δ² (R − δ/3) ≈ π R δ² and
// |S| = π a² = π (2Rδ − δ²) ≈ 2π R δ. Then |F| = (5/4) c V^{1/4} |S| ≈ (5/2) c π^{5/4} R^{5/4}
// δ^{3/2}, which is Hertz's 4/3 E* √R δ^{3/2} (Johnson 1985, eq. 4.23) when
//   c = (8/15) E* π^{−5/4} R*^{−3/4}.
// Two spheres: the lens of two caps has V ≈ π R* δ² and |S| ≈ 2π R* δ with R* = R₁R₂/(R₁+R₂),
// so the same c holds with that R*. The neglected terms are O(δ/R) (−δ/(2R) in |S|, −δ/(12R) in
// V^{1/4}): Hertz's own small-strain order.
//
// R* must be one constant per pair for W to be a potential. For a polyhedron this build takes the
// radius of the sphere of the same volume, R = (3 V_body / 4π)^{1/3} (a faceted sphere tends to
// its own radius; a rock or a cube gets the size of its bulk), and infinity for fixed bodies and
// planes, so R* = R for a body on a fixed target. Away from spheres the law is then a choice, not
// Hertz: the exponents of F(δ) follow from V(δ) and |S| = dV/dδ, F = (5/4) c V^{1/4} dV/dδ:
//   vertex (cone, V ∝ δ³):  F ∝ δ^{11/4};   edge (wedge, V ∝ δ²):  F ∝ δ^{3/2};
//   face (V ∝ δ):           F ∝ δ^{1/4}.
#pragma once

#include <cmath>
#include <numbers>

namespace asperity::contact {

// c of W = c V^{5/4}, J/m^{15/4}; E* in Pa, R* in m.
inline double volume_hertz_coefficient(double e_star, double r_star) {
  return 8.0 / 15.0 * e_star * std::pow(std::numbers::pi, -1.25) * std::pow(r_star, -0.75);
}

// Energy W (J) and dW/dV (Pa) at overlap volume V (m³); zero when apart.
struct VolumeEnergy {
  double energy = 0;
  double slope = 0;
};
inline VolumeEnergy volume_hertz(double volume, double coefficient) {
  if (!(volume > 0)) return {};
  const double q = std::pow(volume, 0.25);
  return {.energy = coefficient * volume * q, .slope = 1.25 * coefficient * q};
}

// Tangential (no-slip) stiffness of volume-hertz's friction, N/m: k_t = 3 (G*/E*) |F_n| / h with
// h = V/|S| the overlap's mean depth (|F_n| in N, |S| in m², V in m³, G* and E* in Pa;
// core/material.hpp). A sphere pressed δ has h = δ/2 and |F_n| = (4/3) E* √R* δ^{3/2}, so
// k_t = 8 G* √(R*δ): Mindlin's (contact/hertz_mindlin.hpp), to the law's O(δ/R). An edge (h = δ/2,
// F ∝ δ^{3/2}) gets 4G*/E* times its tangent normal stiffness, Mindlin's ratio; a face (h = δ,
// F ∝ δ^{1/4}) three times that (docs/physics.md, "Friction").
inline double volume_hertz_tangent_stiffness(double normal_force, double area, double volume,
                                             double g_star, double e_star) {
  if (!(volume > 0)) return 0;
  return 3.0 * g_star / e_star * normal_force * area / volume;
}

// R* of a pair from the two bodies' equivalent radii (m; a fixed body or plane passes infinity).
inline double volume_hertz_radius(double r_a, double r_b) {
  if (std::isinf(r_a)) return r_b;
  if (std::isinf(r_b)) return r_a;
  return r_a * r_b / (r_a + r_b);
}

// Radius of the sphere with the body's volume, m.
inline double equivalent_radius(double body_volume) {
  return std::cbrt(3.0 * body_volume / (4.0 * std::numbers::pi));
}

}  // namespace asperity::contact
