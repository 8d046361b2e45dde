// One sphere contact's Hertz or Hertz–Mindlin force computed whole, with its outcome (total force,
// normal part, dissipated work) and its history update: the scalar law of the sphere DEM, which
// its walls use and its staged sphere–sphere loop (dem/mindlin_columns.hpp) reproduces bit for bit.
#pragma once

#include "solver/contact/hertz.hpp"
#include "solver/contact/hertz_mindlin.hpp"
#include "solver/contact/tangential_spring.hpp"
#include "solver/core/vec.hpp"

namespace asperity::dem {

struct ContactOutcome {
  Vec3 force = Vec3::Zero();         // on body 1, N
  Vec3 normal_force = Vec3::Zero();  // its normal part (elastic + normal damping), N
  double dissipated = 0;             // this step, J
};

// A contact's outcome from its normal and tangential law forces: the total force, and the work of
// the non-elastic normal part over this step's overlap change by the trapezoidal rule (the rule
// velocity Verlet applies to the kinetic energy), so the energy balance closes to O(dt²) rather
// than O(dt). Updates the contact's history (spring, last viscous force).
inline ContactOutcome outcome(const contact::NormalForce& fn, const contact::TangentialForce& ft,
                              const Vec3& n, double rate, Vec3& spring, double& viscous,
                              double dt) {
  ContactOutcome out;
  out.normal_force = fn.force * n;
  const double viscous_now = fn.force - fn.elastic;
  out.dissipated = 0.5 * (viscous + viscous_now) * rate * dt;
  viscous = viscous_now;
  spring = ft.spring;
  out.force = out.normal_force + ft.force;
  out.dissipated += ft.dissipated;
  return out;
}

// Hertz (mindlin false) or Hertz–Mindlin force on body 1 of one touching contact, from the pair's
// coefficients (contact/hertz_mindlin.hpp, a pure function), its geometry and history.
// n: unit normal from body 2 towards body 1; overlap, m; v_rel: velocity of body 1 relative to
// body 2 at the contact point, m/s; rate_end: the overlap rate the dashpot sees, m/s; spring
// (N) and viscous (N): last step's on entry, this step's on return.
template <bool mindlin>
[[gnu::always_inline]] inline ContactOutcome hertz_contact(
    const contact::HertzMindlinCoefficients& c, const Vec3& n, double overlap, const Vec3& v_rel,
    double rate_end, Vec3& spring, double& viscous, double dt) {
  const double rate = -v_rel.dot(n);
  contact::NormalForce fn;
  contact::TangentialForce ft;
  if constexpr (mindlin) {
    const Vec3 slip = v_rel - v_rel.dot(n) * n;
    const contact::HertzMindlinForce f = contact::hertz_mindlin(
        overlap, rate_end, slip, contact::rotate_into_tangent_plane(spring, n), dt, c);
    fn = f.normal;
    ft = f.tangential;
  } else {
    fn = contact::hertz_normal(overlap, rate_end, c.normal);
  }
  return outcome(fn, ft, n, rate, spring, viscous, dt);
}

}  // namespace asperity::dem
