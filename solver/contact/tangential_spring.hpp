// Incremental tangential spring with a Coulomb cap: Mindlin's no-slip stiffness k_t = 8 G* a for
// Hertz–Mindlin (as in LIGGGHTS and YADE's Law2_ScGeom_MindlinPhys_Mindlin), or a constant k_t for
// the linear law.
#pragma once

#include <algorithm>
#include <cmath>

#include "solver/core/vec.hpp"

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

// Carries last step's spring force into the current tangent plane (normal n, unit), keeping its
// magnitude: the contact frame turned, the stored elastic force did not change (the rotation
// step of Luding 2008, Granular Matter 10:235, §2.2.2, and of YADE's ScGeom::rotate).
// (One root and one quotient: the factor |F| / |s| as √(|F|² / |s|²).)
inline Vec3 rotate_into_tangent_plane(const Vec3& spring, const Vec3& n) {
  Vec3 s = spring - spring.dot(n) * n;
  if (const double ss = s.squaredNorm(); ss > 0) s *= std::sqrt(spring.squaredNorm() / ss);
  return s;
}

// Energy stored in a spring force F_s of stiffness k_t: |F_s|²/(2 k_t), J (0 without stiffness).
inline double spring_energy(const Vec3& spring, double stiffness) {
  return stiffness > 0 ? spring.squaredNorm() / (2 * stiffness) : 0;
}

// spring: the previous spring force already rotated into the current tangent plane.
// slip_velocity: tangential velocity of body 1 relative to body 2 at the contact point, m/s.
// Incremental law F_s ← F_s − k_t v_t dt. Sticking (|F_s + F_d| ≤ μ F_n) the force is spring plus
// dashpot; the dashpot dissipates −F_d·v_t dt and the spring none (its path is linear, so the
// trapezoidal work equals its energy change exactly). Sliding, the total is μ F_n along the trial
// force, carried by the spring alone, and the work of sliding is μ F_n times the slip length
// (|F_s,trial| − μ F_n)/k_t: the usual plastic-slip split of the trial displacement.
inline TangentialForce tangential_spring(const Vec3& spring, const Vec3& slip_velocity, double dt,
                                         double normal_force, const TangentialParams& p) {
  TangentialForce out;
  const Vec3 trial = spring - p.stiffness * dt * slip_velocity;
  const Vec3 fd = -p.damping * slip_velocity;
  const double cap = p.friction * normal_force;
  // |F_s + F_d| > μ F_n compared squared (both sides ≥ 0): the root only where it slides.
  if ((trial + fd).squaredNorm() > cap * cap) {
    const double total = (trial + fd).norm();
    out.sliding = true;
    out.spring = total > 0 ? Vec3(cap / total * (trial + fd)) : Vec3::Zero();
    out.force = out.spring;
    if (p.stiffness > 0) out.dissipated = cap * std::max(0.0, trial.norm() - cap) / p.stiffness;
  } else {
    out.spring = trial;
    out.force = trial + fd;
    out.dissipated = -fd.dot(slip_velocity) * dt;
  }
  out.energy = spring_energy(out.spring, p.stiffness);
  return out;
}

}  // namespace asperity::contact
