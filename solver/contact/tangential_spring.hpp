// Incremental tangential spring with a Coulomb cap: Mindlin's no-slip stiffness k_t = 8 G* a for
// Hertz–Mindlin (as in LIGGGHTS and YADE's Law2_ScGeom_MindlinPhys_Mindlin), or a constant k_t for
// the linear law.
#pragma once

#include <cmath>

#include "core/vec.hpp"

namespace asperity::contact {

struct TangentialParams {
  double stiffness = 0;  // k_t, N/m (Hertz–Mindlin: 8 G* a, a = √(R* δ), updated every step)
  double damping = 0;    // c_t, N·s/m (viscous, not stored in the spring)
  double friction = 0;   // Coulomb μ
};

struct TangentialForce {
  Vec3 spring = Vec3::Zero();  // new elastic spring force (history), N
  Vec3 force = Vec3::Zero();   // total tangential force on body 1, N
  double dissipated = 0;       // work of sliding and viscous damping this step, J
  double energy = 0;           // stored spring energy |F_s|²/(2 k_t), J
  bool sliding = false;
};

// spring: the previous spring force already rotated into the current tangent plane.
// slip_velocity: tangential velocity of body 1 relative to body 2 at the contact point, m/s.
// Incremental law F_s ← F_s − k_t v_t dt; if |F_s + F_d| > μ F_n the total is scaled to μ F_n,
// the spring keeps the capped force. Dissipation is the work the relative motion did on the contact
// minus the change of stored spring energy, so the energy balance closes by construction.
inline TangentialForce tangential_spring(const Vec3& spring, const Vec3& slip_velocity, double dt,
                                         double normal_force, const TangentialParams& p) {
  TangentialForce out;
  Vec3 fs = spring - p.stiffness * dt * slip_velocity;
  const Vec3 fd = -p.damping * slip_velocity;
  const double cap = p.friction * normal_force;
  const double trial = (fs + fd).norm();
  if (trial > cap) {
    // Coulomb: total force of magnitude μ F_n, spring kept equal to it (no viscous part in slip).
    out.sliding = true;
    const Vec3 dir = trial > 0 ? Vec3((fs + fd) / trial) : Vec3::Zero();
    const Vec3 capped = cap * dir;
    fs = capped;
    out.force = capped;
  } else {
    out.force = fs + fd;
  }
  out.spring = fs;
  const double inv2k = p.stiffness > 0 ? 1.0 / (2 * p.stiffness) : 0;
  out.energy = fs.squaredNorm() * inv2k;
  out.dissipated = -out.force.dot(slip_velocity) * dt - (out.energy - spring.squaredNorm() * inv2k);
  return out;
}

}  // namespace asperity::contact
