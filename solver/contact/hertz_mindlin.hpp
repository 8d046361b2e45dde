// Hertz–Mindlin: Hertz's normal force (contact/hertz.hpp) with Mindlin's no-slip tangential
// stiffness k_t = 8 G* a, a = √(R* δ) (Mindlin 1949), a Coulomb cap (contact/tangential_spring.hpp)
// and viscous damping of the same Tsuji form in both directions. A pure function of one contact:
// the law LIGGGHTS calls `model hertz tangential history` and YADE
// Law2_ScGeom_MindlinPhys_Mindlin.
#pragma once

#include <cmath>

#include "solver/contact/hertz.hpp"
#include "solver/contact/tangential_spring.hpp"
#include "solver/core/vec.hpp"

namespace asperity::contact {

struct HertzMindlinParams {
  double young_eff = 0;   // E*, Pa
  double shear_eff = 0;   // G*, Pa
  double radius_eff = 0;  // R*, m
  double mass_eff = 0;    // m*, kg
  double zeta = 0;        // Tsuji damping (restitution_damping.hpp), both directions
  double friction = 0;    // Coulomb μ
};

struct HertzMindlinForce {
  NormalForce normal;          // magnitude along n
  TangentialForce tangential;  // in the tangent plane, with the new spring (history)
};

// What of a Hertz–Mindlin pair does not change while it touches (computed once per pair of bodies).
// k_t = 8 G* √R* δ^{1/2} and c_t = ζ √(m* k_t / 1.5) = ζ √(8 G* √R* m* / 1.5) δ^{1/4}: the factors
// before the powers of δ are the pair's, so a contact takes no root beyond δ^{1/2} and δ^{1/4}.
struct HertzMindlinCoefficients {
  HertzCoefficients normal;  // K, ζ √(m* K)
  double shear = 0;          // 8 G* √R*, N/m^{3/2}: k_t = shear · δ^{1/2}
  double shear_damping = 0;  // ζ √(8 G* √R* m* / 1.5): c_t = shear_damping · δ^{1/4}
  double radius_eff = 0;     // R*, m
  double mass_eff = 0;       // m*, kg
  double friction = 0;
};

inline HertzMindlinCoefficients hertz_mindlin_coefficients(const HertzMindlinParams& p) {
  return {.normal = hertz_coefficients({.young_eff = p.young_eff,
                                        .radius_eff = p.radius_eff,
                                        .mass_eff = p.mass_eff,
                                        .zeta = p.zeta}),
          .shear = 8.0 * p.shear_eff * std::sqrt(p.radius_eff),
          .shear_damping =
              p.zeta * std::sqrt(8.0 * p.shear_eff * std::sqrt(p.radius_eff) * p.mass_eff / 1.5),
          .radius_eff = p.radius_eff,
          .mass_eff = p.mass_eff,
          .friction = p.friction};
}

// Mindlin's no-slip tangent stiffness k_t = 8 G* a, a = √(R* δ), N/m (also what the stored
// spring energy |F_s|²/(2 k_t) is measured with).
inline double mindlin_stiffness(const HertzMindlinCoefficients& c, double overlap) {
  return c.shear * std::sqrt(overlap);
}

// overlap δ > 0 (m); overlap_rate δ̇ (m/s, approaching > 0); slip_velocity: tangential velocity
// of body 1 relative to body 2 at the contact point (m/s); spring: last step's spring force
// rotated into the current tangent plane (rotate_into_tangent_plane); dt the step (s).
// The tangential dashpot c_t = ζ √(m* k_t / 1.5) is the normal one's Tsuji coefficient with the
// tangent stiffness k_t in place of S_n = 3/2 K δ^{1/2}.
inline HertzMindlinForce hertz_mindlin(double overlap, double overlap_rate,
                                       const Vec3& slip_velocity, const Vec3& spring, double dt,
                                       const HertzMindlinCoefficients& c) {
  HertzMindlinForce out;
  const double sqrt_d = std::sqrt(overlap), fourth_d = std::sqrt(sqrt_d);
  out.normal = hertz_normal(overlap, sqrt_d, fourth_d, overlap_rate, c.normal);
  const double kt = c.shear * sqrt_d;
  const double ct = c.shear_damping * fourth_d;
  out.tangential = tangential_spring(spring, slip_velocity, dt, out.normal.force,
                                     {.stiffness = kt, .damping = ct, .friction = c.friction});
  return out;
}

inline HertzMindlinForce hertz_mindlin(double overlap, double overlap_rate,
                                       const Vec3& slip_velocity, const Vec3& spring, double dt,
                                       const HertzMindlinParams& p) {
  return hertz_mindlin(overlap, overlap_rate, slip_velocity, spring, dt,
                       hertz_mindlin_coefficients(p));
}

}  // namespace asperity::contact
