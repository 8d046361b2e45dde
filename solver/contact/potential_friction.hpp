// Coulomb friction of one potential contact between two tetrahedra (Munjiza's distributed
// potential, munjiza_potential.hpp), a pure function of the pair's kinematics: a tangential spring
// with a Coulomb cap (tangential_spring.hpp) at the pressure centroid, its stiffness the pair's
// secant normal stiffness |F_n| / depth (so that the tangential and normal penalty layers have the
// same compliance), acting on the relative velocity of the two elements there, and distributed to
// each element's nodes by its barycentric coordinates (docs/physics.md, "Coulomb friction").
#pragma once

#include <array>

#include <Eigen/Core>

#include "solver/contact/munjiza_potential.hpp"
#include "solver/contact/tangential_spring.hpp"
#include "solver/core/vec.hpp"

namespace asperity::contact {

struct PotentialFriction {
  std::array<Vec3, 4> on_a, on_b;  // the friction force on each element's nodes, N
  TangentialForce tangential;      // its total on a, the new spring, energy and dissipated work
};

// a, b: the two elements' nodes; va, vb: their nodes' velocities (m/s); point: the pressure
// centroid; normal_force_a: the potential force on a (N, nonzero); depth: the pair's depth (m, >
// 0); spring: last step's tangential spring force on a (N); mu: Coulomb's coefficient.
inline PotentialFriction potential_friction(const TetNodes& a, const TetNodes& b,
                                            const std::array<Vec3, 4>& va,
                                            const std::array<Vec3, 4>& vb, const Vec3& point,
                                            const Vec3& normal_force_a, double depth,
                                            const Vec3& spring, double dt, double mu) {
  const double fn_mag = normal_force_a.norm();
  const Vec3 n = normal_force_a / fn_mag;
  const Eigen::Vector4d la = barycentric(a, point), lb = barycentric(b, point);
  Vec3 vpa = Vec3::Zero(), vpb = Vec3::Zero();
  for (int i = 0; i < 4; ++i) {
    vpa += la[i] * va[i];
    vpb += lb[i] * vb[i];
  }
  const Vec3 vr = vpa - vpb;
  const Vec3 vt = vr - vr.dot(n) * n;
  PotentialFriction out;
  out.tangential = tangential_spring(rotate_into_tangent_plane(spring, n), vt, dt, fn_mag,
                                     {.stiffness = fn_mag / depth, .damping = 0, .friction = mu});
  for (int i = 0; i < 4; ++i) {
    out.on_a[i] = la[i] * out.tangential.force;
    out.on_b[i] = lb[i] * out.tangential.force;
  }
  return out;
}

}  // namespace asperity::contact
