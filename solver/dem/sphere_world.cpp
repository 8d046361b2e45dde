// Rigid-sphere DEM step: broad phase (Verlet list on a cell grid) → contact forces → integrate.
#include "solver/dem/sphere_world.hpp"

#include <algorithm>
#include <cmath>

#include "solver/contact/hertz.hpp"
#include "solver/contact/hertz_mindlin.hpp"
#include "solver/contact/linear_spring_dashpot.hpp"
#include "solver/contact/tangential_spring.hpp"
#include "solver/core/error.hpp"
#include "solver/core/ticks.hpp"
#include "solver/dem/cell_grid.hpp"

namespace asperity::dem {
namespace {

// What one contact needs, whatever the pair: geometry and the effective quantities.
struct ContactGeometry {
  Vec3 normal;        // unit, from body 2 towards body 1
  double overlap;     // m
  Vec3 arm1, arm2;    // contact point relative to each centre, m
  double radius_eff;  // R*, m
  double mass_eff;    // m*, kg
};

struct ContactOutcome {
  Vec3 force = Vec3::Zero();         // on body 1, N
  Vec3 normal_force = Vec3::Zero();  // its normal part (elastic + normal damping), N
  double rate = 0;                   // δ̇, m/s
  double energy = 0;                 // stored, J
  double dissipated = 0;             // this step, J
};

// Normal and tangential force on body 1 for one touching contact: the scene's law (a pure
// function in contact/) applied to this pair's geometry, effective quantities and history.
ContactOutcome contact_force(const SphereWorld& world, const ContactGeometry& g,
                             const PairConstants& pc, const Vec3& v_rel, double rate_end,
                             Vec3& spring, double& viscous, double dt) {
  ContactOutcome out;
  const Vec3& n = g.normal;
  out.rate = -v_rel.dot(n);
  const Vec3 slip = v_rel - v_rel.dot(n) * n;
  contact::NormalForce fn;
  contact::TangentialForce ft;
  if (world.law.normal == contact::NormalLaw::hertz && world.law.tangential) {
    const contact::HertzMindlinForce f = contact::hertz_mindlin(
        g.overlap, rate_end, slip, contact::rotate_into_tangent_plane(spring, n), dt,
        {.young_eff = pc.young_eff,
         .shear_eff = pc.shear_eff,
         .radius_eff = g.radius_eff,
         .mass_eff = g.mass_eff,
         .zeta = pc.zeta,
         .friction = pc.friction});
    fn = f.normal;
    ft = f.tangential;
  } else if (world.law.normal == contact::NormalLaw::hertz) {
    fn = contact::hertz_normal(g.overlap, rate_end,
                               {.young_eff = pc.young_eff,
                                .radius_eff = g.radius_eff,
                                .mass_eff = g.mass_eff,
                                .zeta = pc.zeta});
  } else {
    fn = contact::linear_normal(g.overlap, rate_end,
                                {.kn = world.law.kn, .mass_eff = g.mass_eff, .zeta = pc.zeta});
    // The linear law's tangential spring: constant k_t, dashpot ζ √(m* k_t).
    ft = contact::tangential_spring(contact::rotate_into_tangent_plane(spring, n), slip, dt,
                                    fn.force,
                                    {.stiffness = world.law.kt,
                                     .damping = pc.zeta * std::sqrt(g.mass_eff * world.law.kt),
                                     .friction = pc.friction});
  }
  out.normal_force = fn.force * n;
  out.energy = fn.energy;
  // Work of the non-elastic part of the normal force over this step's overlap change, by the
  // trapezoidal rule (the rule velocity Verlet applies to the kinetic energy), so the energy
  // balance closes to O(dt²) rather than O(dt).
  const double viscous_now = fn.force - fn.elastic;
  out.dissipated = 0.5 * (viscous + viscous_now) * out.rate * dt;
  viscous = viscous_now;
  spring = ft.spring;
  out.force = out.normal_force + ft.force;
  out.energy += ft.energy;
  out.dissipated += ft.dissipated;
  return out;
}

void rebuild_pairs(SphereWorld& world) {
  std::vector<PairContact> old = std::move(world.pairs);
  world.pairs = neighbour_pairs(world.x, world.radius, world.fixed, world.skin);
  // Carry the tangential history across (both lists sorted by (i, j)).
  auto it = old.begin();
  for (PairContact& p : world.pairs) {
    while (it != old.end() && std::tie(it->i, it->j) < std::tie(p.i, p.j)) ++it;
    if (it != old.end() && it->i == p.i && it->j == p.j) {
      p.spring = it->spring;
      p.viscous = it->viscous;
      p.touching = it->touching;
    }
  }
  world.x_at_build = world.x;
  ++world.rebuilds;
}

bool needs_rebuild(const SphereWorld& world) {
  if (world.x_at_build.cols() != world.x.cols()) return true;
  const double limit = 0.25 * world.skin * world.skin;
  for (int i = 0; i < world.size(); ++i) {
    if ((world.x.col(i) - world.x_at_build.col(i)).squaredNorm() > limit) return true;
  }
  return false;
}

// Dashpots see the velocity at the end of the step, predicted with last step's acceleration
// (v_{n+1} ≈ v_{n+½} + ½ dt a_n): a second-order estimate where the half-step velocity alone
// lags by ½ dt a and biases damped peaks and restitution at coarse steps.
void predict_end_velocity(SphereWorld& w, double dt) {
  w.v_end = w.v;
  for (int i = 0; i < w.size(); ++i) {
    if (!w.fixed[i]) w.v_end.col(i) += 0.5 * dt * (w.force.col(i) / w.mass[i] + w.gravity);
  }
}

// Sphere–sphere contacts of the candidate pairs.
void pair_forces(SphereWorld& w, double dt) {
  const int nm = static_cast<int>(w.materials.size());
  for (PairContact& p : w.pairs) {
    const int i = p.i, j = p.j;
    const Vec3 d = w.x.col(i) - w.x.col(j);
    const double dist = d.norm();
    const double overlap = w.radius[i] + w.radius[j] - dist;
    if (overlap <= 0 || dist == 0) {
      w.contacts.gap(w.body[i], w.body[j], overlap);
      p.touching = false;
      p.spring.setZero();
      p.viscous = 0;
      continue;
    }
    const Vec3 n = d / dist;
    w.max_overlap_ratio =
        std::max(w.max_overlap_ratio, overlap / std::min(w.radius[i], w.radius[j]));
    const double mi = w.fixed[i] ? 0 : w.mass[i], mj = w.fixed[j] ? 0 : w.mass[j];
    ContactGeometry g{.normal = n,
                      .overlap = overlap,
                      .arm1 = -(w.radius[i] - 0.5 * overlap) * n,
                      .arm2 = (w.radius[j] - 0.5 * overlap) * n,
                      .radius_eff = w.radius[i] * w.radius[j] / (w.radius[i] + w.radius[j]),
                      .mass_eff = mi == 0 ? mj : (mj == 0 ? mi : mi * mj / (mi + mj))};
    const Vec3 v_rel =
        (w.v.col(i) + w.w.col(i).cross(g.arm1)) - (w.v.col(j) + w.w.col(j).cross(g.arm2));
    const double rate_end = -(w.v_end.col(i) - w.v_end.col(j)).dot(n);
    const ContactOutcome c = contact_force(w, g, w.pair[w.material[i] * nm + w.material[j]], v_rel,
                                           rate_end, p.spring, p.viscous, dt);
    w.force.col(i) += c.force;
    w.force.col(j) -= c.force;
    w.torque.col(i) += g.arm1.cross(c.force);
    w.torque.col(j) -= g.arm2.cross(c.force);
    w.contact_energy += c.energy;
    w.dissipated += c.dissipated;
    ++w.contact_updates;
    p.touching = true;
    w.contacts.add(w.body[i], w.body[j], c.force, c.normal_force, overlap);
  }
}

// Overlap (m) of a sphere (centre x, radius r) with a wall, and the wall's outward normal there.
double wall_overlap(const Wall& wall, const Vec3& x, double r, Vec3& normal) {
  if (wall.kind == WallKind::plane) {
    normal = wall.b;
    return r - (x - wall.a).dot(normal);
  }
  const Vec3 closest = x.cwiseMax(wall.a).cwiseMin(wall.b);
  const Vec3 diff = x - closest;
  const double dist = diff.norm();
  if (dist > 0) {
    normal = diff / dist;
    return r - dist;
  }
  // Centre inside the box: push out through the nearest face.
  const Vec3 lo = x - wall.a, hi = wall.b - x;
  Eigen::Index kl, kh;
  const double dl = lo.minCoeff(&kl), dh = hi.minCoeff(&kh);
  normal = Vec3::Zero();
  if (dl < dh)
    normal[kl] = -1;
  else
    normal[kh] = 1;
  return r + std::min(dl, dh);
}

// Sphere–wall contacts (planes and boxes) of every moving sphere.
void wall_forces(SphereWorld& w, double dt) {
  const int nm = static_cast<int>(w.materials.size());
  const int n = w.size();
  for (std::size_t k = 0; k < w.walls.size(); ++k) {
    const Wall& wall = w.walls[k];
    for (int i = 0; i < n; ++i) {
      if (w.fixed[i]) continue;
      WallContact& h = w.wall_contacts[k * n + i];
      Vec3 normal;
      const double overlap = wall_overlap(wall, w.x.col(i), w.radius[i], normal);
      if (overlap <= 0) {
        w.contacts.gap(w.body[i], wall.body, overlap);
        h.touching = false;
        h.spring.setZero();
        h.viscous = 0;
        continue;
      }
      w.max_overlap_ratio = std::max(w.max_overlap_ratio, overlap / w.radius[i]);
      ContactGeometry g{.normal = normal,
                        .overlap = overlap,
                        .arm1 = -(w.radius[i] - 0.5 * overlap) * normal,
                        .arm2 = Vec3::Zero(),
                        .radius_eff = w.radius[i],
                        .mass_eff = w.mass[i]};
      const Vec3 v_rel = w.v.col(i) + w.w.col(i).cross(g.arm1);
      const double rate_end = -w.v_end.col(i).dot(normal);
      const ContactOutcome c = contact_force(w, g, w.pair[w.material[i] * nm + wall.material],
                                             v_rel, rate_end, h.spring, h.viscous, dt);
      w.force.col(i) += c.force;
      w.torque.col(i) += g.arm1.cross(c.force);
      w.contact_energy += c.energy;
      w.dissipated += c.dissipated;
      ++w.contact_updates;
      h.touching = true;
      w.contacts.add(w.body[i], wall.body, c.force, c.normal_force, overlap);
    }
  }
}

void compute_forces(SphereWorld& w, double dt) {
  predict_end_velocity(w, dt);
  w.force.setZero();
  w.torque.setZero();
  w.contact_energy = 0;
  w.contacts.reset(w.contacts.size());
  pair_forces(w, dt);
  wall_forces(w, dt);
}

}  // namespace

void initialise(SphereWorld& world) {
  const int n = world.size();
  const int nm = static_cast<int>(world.materials.size());
  world.pair.assign(nm * nm, {});
  for (int a = 0; a < nm; ++a) {
    for (int b = 0; b < nm; ++b) {
      const Material &ma = world.materials[a], &mb = world.materials[b];
      PairConstants& pc = world.pair[a * nm + b];
      pc.young_eff = effective_young(ma, mb);
      pc.shear_eff = effective_shear(ma, mb);
      pc.friction = world.law.friction.value_or(pair_friction(ma, mb));
      pc.zeta = contact::damping_for_restitution(
          world.law.normal, world.law.restitution.value_or(pair_restitution(ma, mb)));
    }
  }
  world.force = Eigen::Matrix3Xd::Zero(3, n);
  world.torque = Eigen::Matrix3Xd::Zero(3, n);
  world.orientation.assign(n, Quat::Identity());
  double r_min = 1e300;
  for (double r : world.radius) r_min = std::min(r_min, r);
  // A skin of a fifth of the smallest radius: few rebuilds, few extra candidate pairs.
  world.skin = n > 0 ? 0.2 * r_min : 0;
  world.wall_contacts.assign(world.walls.size() * n, {});
  world.x_initial = world.x;
  // Contact output is per scene body: every sphere and wall must name its body.
  int bodies = 0;
  ASPERITY_CHECK(world.body.size() == static_cast<std::size_t>(n));
  for (int b : world.body) {
    ASPERITY_CHECK(b >= 0);
    bodies = std::max(bodies, b + 1);
  }
  for (const Wall& wall : world.walls) {
    ASPERITY_CHECK(wall.body >= 0);
    bodies = std::max(bodies, wall.body + 1);
  }
  world.contacts.reset(bodies);
  rebuild_pairs(world);
  compute_forces(world, 0.0);
}

void step(SphereWorld& world, double dt) {
  const int n = world.size();
  const std::uint64_t t0 = ticks();
  for (int i = 0; i < n; ++i) {
    if (world.fixed[i]) continue;
    world.v.col(i) += 0.5 * dt * (world.force.col(i) / world.mass[i] + world.gravity);
    world.w.col(i) += 0.5 * dt * world.torque.col(i) / world.inertia[i];
    world.x.col(i) += dt * world.v.col(i);
    const Vec3 spin = world.w.col(i) * dt;
    if (const double angle = spin.norm(); angle > 0) {
      world.orientation[i] =
          (Quat(Eigen::AngleAxisd(angle, spin / angle)) * world.orientation[i]).normalized();
    }
  }
  const std::uint64_t t1 = ticks();
  if (needs_rebuild(world)) rebuild_pairs(world);
  const std::uint64_t t2 = ticks();
  compute_forces(world, dt);
  const std::uint64_t t3 = ticks();
  for (int i = 0; i < n; ++i) {
    if (world.fixed[i]) continue;
    world.v.col(i) += 0.5 * dt * (world.force.col(i) / world.mass[i] + world.gravity);
    world.w.col(i) += 0.5 * dt * world.torque.col(i) / world.inertia[i];
  }
  const std::uint64_t t4 = ticks();
  world.profile.integrate += (t1 - t0) + (t4 - t3);
  world.profile.broad_phase += t2 - t1;
  world.profile.contact += t3 - t2;
  world.time += dt;
  ++world.steps;
}

EnergyBalance energy(const SphereWorld& world) {
  EnergyBalance e;
  for (int i = 0; i < world.size(); ++i) {
    if (world.fixed[i]) continue;
    e.kinetic += 0.5 * world.mass[i] * world.v.col(i).squaredNorm() +
                 0.5 * world.inertia[i] * world.w.col(i).squaredNorm();
    e.gravity -= world.mass[i] * world.gravity.dot(world.x.col(i) - world.x_initial.col(i));
  }
  e.contact = world.contact_energy;
  e.dissipated = world.dissipated;
  return e;
}

}  // namespace asperity::dem
