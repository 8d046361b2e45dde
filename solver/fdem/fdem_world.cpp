// FEM/DEM step: broad phase → contact (Munjiza potential + Coulomb friction) → internal forces
// (neo-Hookean tetrahedra) → integrate (central differences; rigid bodies in 6 DOF).
#include "solver/fdem/fdem_world.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "solver/core/ticks.hpp"
#include "solver/fdem/broad_phase.hpp"
#include "solver/fdem/world_phases.hpp"

namespace asperity::fdem {
namespace {

void place_rigid_nodes(World& w, const RigidBody& rb) {
  const Body& b = w.bodies[rb.body];
  const Mat3 r = rb.orientation.toRotationMatrix();
  for (int i = b.node_begin; i < b.node_end; ++i) {
    const Vec3 arm = r * rb.r_body.col(i - b.node_begin);
    w.x.col(i) = rb.centre + arm;
    w.v.col(i) = rb.velocity + rb.omega.cross(arm);
  }
}

Mat3 world_inertia(const RigidBody& rb) {
  const Mat3 r = rb.orientation.toRotationMatrix();
  return r * rb.inertia_body * r.transpose();
}

bool needs_rebuild(const World& w) {
  const double limit = 0.25 * w.skin * w.skin;
  return ((w.x - w.x_at_build).colwise().squaredNorm().array() > limit).any();
}

void internal_forces(World& w, double dt) {
  double elastic = 0;
  for (const fem::TetElements& e : w.elements) {
    const fem::InternalForceResult r = fem::add_internal_forces(e, w.x, w.v, w.f, w.want_energy);
    elastic += r.energy;
    w.dissipated -= r.damping_power * dt;
    if (r.inverted >= 0 && w.failure.empty()) {
      const int body = w.node_body[e.tets(0, r.inverted)];
      std::ostringstream s;
      s << "body \"" << w.bodies[body].name << "\" element " << r.inverted
        << " inverted (J = " << r.inverted_j << ") at t = " << w.time << " s";
      w.failure = s.str();
    }
    w.max_rotation = std::max(w.max_rotation, r.max_rotation);
    if (r.max_rotation > fem::kLinearMaxRotation && w.failure.empty()) {
      const int body = w.node_body[e.tets(0, r.rotated)];
      std::ostringstream s;
      s << "body \"" << w.bodies[body].name << "\" element " << r.rotated << " rotated by "
        << std::asin(std::min(1.0, r.max_rotation)) << " rad at t = " << w.time
        << " s, past the linear law's " << std::asin(fem::kLinearMaxRotation)
        << " rad (it is not frame-indifferent: use \"neo-hookean\" for bodies that rotate)";
      w.failure = s.str();
    }
  }
  if (w.want_energy) w.elastic_energy = elastic;
}

// Half kick of every moving body with the current forces.
void kick(World& w, double half_dt) {
  const int n = w.node_count();
  for (int i = 0; i < n; ++i) {
    if (w.inv_mass[i] > 0) w.v.col(i) += half_dt * (w.f.col(i) * w.inv_mass[i] + w.gravity);
  }
  for (RigidBody& rb : w.rigid) {
    rb.velocity += half_dt * (rb.force / rb.mass + w.gravity);
    // Euler's equations in the world frame: I ω̇ = τ − ω × I ω.
    const Mat3 iw = world_inertia(rb);
    rb.omega += half_dt * iw.ldlt().solve(rb.torque - rb.omega.cross(iw * rb.omega));
  }
}

void drift(World& w, double dt) {
  const int n = w.node_count();
  for (int i = 0; i < n; ++i) {
    if (w.inv_mass[i] > 0) w.x.col(i) += dt * w.v.col(i);
  }
  for (RigidBody& rb : w.rigid) {
    rb.centre += dt * rb.velocity;
    const Vec3 spin = rb.omega * dt;
    if (const double angle = spin.norm(); angle > 0) {
      rb.orientation = (Quat(Eigen::AngleAxisd(angle, spin / angle)) * rb.orientation).normalized();
    }
    place_rigid_nodes(w, rb);
  }
}

}  // namespace

namespace detail {

void rebuild_pairs(World& w) {
  std::vector<std::uint8_t> fixed(w.bodies.size());
  for (std::size_t b = 0; b < w.bodies.size(); ++b) fixed[b] = w.bodies[b].kind == BodyKind::fixed;
  std::vector<TetPair> old = std::move(w.pairs);
  w.pairs = candidate_pairs(w.x, w.surface_tets, w.surface_tet_body, fixed, w.skin);
  // Carry the friction history across (both lists sorted by (a, b)).
  auto it = old.begin();
  for (TetPair& p : w.pairs) {
    while (it != old.end() && (it->a < p.a || (it->a == p.a && it->b < p.b))) ++it;
    if (it != old.end() && it->a == p.a && it->b == p.b) p.spring = it->spring;
  }
  w.x_at_build = w.x;
  ++w.rebuilds;
}

// Rigid bodies: total force and torque about the centre from their nodes' forces.
void reduce_rigid(World& w) {
  for (RigidBody& rb : w.rigid) {
    const Body& b = w.bodies[rb.body];
    rb.force = rb.volume_force;
    rb.torque = rb.volume_torque;
    for (int i = b.node_begin; i < b.node_end; ++i) {
      rb.force += w.f.col(i);
      rb.torque += (w.x.col(i) - rb.centre).cross(w.f.col(i));
    }
  }
}

void compute_forces(World& w, double dt) {
  w.f.setZero();
  const std::uint64_t t0 = ticks();
  if (w.law == ContactLaw::potential) {
    potential_contact_forces(w, dt);
  } else {
    volume_contact_forces(w, dt);
  }
  if (w.keep_contact_force) w.f_contact = w.f;  // f held the contact forces only, so far
  const std::uint64_t t1 = ticks();
  internal_forces(w, dt);
  w.profile.contact += t1 - t0;
  w.profile.internal += ticks() - t1;
}

}  // namespace detail

void step(World& w, double dt) {
  if (!w.failure.empty()) return;
  const std::uint64_t t0 = ticks();
  kick(w, 0.5 * dt);
  drift(w, dt);
  const std::uint64_t t1 = ticks();
  if (needs_rebuild(w)) detail::rebuild_pairs(w);
  const std::uint64_t t2 = ticks();
  detail::compute_forces(w, dt);  // contact, then internal forces, each timed
  const std::uint64_t t3 = ticks();
  detail::reduce_rigid(w);
  kick(w, 0.5 * dt);
  for (const RigidBody& rb : w.rigid) place_rigid_nodes(w, rb);
  w.profile.integrate += (t1 - t0) + (ticks() - t3);
  w.profile.broad_phase += t2 - t1;
  w.time += dt;
  ++w.steps;
}

EnergyBalance energy(const World& w) {
  EnergyBalance e;
  for (int i = 0; i < w.node_count(); ++i) {
    if (w.inv_mass[i] > 0) {
      e.kinetic += 0.5 * w.mass[i] * w.v.col(i).squaredNorm();
      e.gravity -= w.mass[i] * w.gravity.dot(w.x.col(i) - w.x_initial.col(i));
    }
  }
  for (const RigidBody& rb : w.rigid) {
    e.kinetic += 0.5 * rb.mass * rb.velocity.squaredNorm() +
                 0.5 * rb.omega.dot(world_inertia(rb) * rb.omega);
    e.gravity -= rb.mass * w.gravity.dot(rb.centre - rb.centre_initial);
  }
  e.elastic = w.elastic_energy;
  e.contact = w.contact_energy;
  e.dissipated = w.dissipated;
  return e;
}

Vec3 momentum(const World& w) {
  Vec3 p = Vec3::Zero();
  for (int i = 0; i < w.node_count(); ++i) {
    if (w.inv_mass[i] > 0) p += w.mass[i] * w.v.col(i);
  }
  for (const RigidBody& rb : w.rigid) p += rb.mass * rb.velocity;
  return p;
}

Vec3 body_velocity(const World& w, int body) {
  const Body& b = w.bodies[body];
  if (b.kind == BodyKind::rigid) return w.rigid[b.rigid].velocity;
  if (b.kind == BodyKind::fixed) return Vec3::Zero();
  Vec3 p = Vec3::Zero();
  double m = 0;
  for (int i = b.node_begin; i < b.node_end; ++i) p += w.mass[i] * w.v.col(i), m += w.mass[i];
  return p / m;
}

Vec3 body_centre(const World& w, int body) {
  const Body& b = w.bodies[body];
  if (b.kind == BodyKind::rigid) return w.rigid[b.rigid].centre;
  Vec3 c = Vec3::Zero();
  double m = 0;
  for (int i = b.node_begin; i < b.node_end; ++i) {
    const double mi = b.kind == BodyKind::fixed ? 1.0 : w.mass[i];
    c += mi * w.x.col(i), m += mi;
  }
  return c / m;
}

}  // namespace asperity::fdem
