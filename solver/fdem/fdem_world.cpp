// FEM/DEM step: broad phase → contact (Munjiza potential + Coulomb friction) → internal forces
// (neo-Hookean tetrahedra) → integrate (central differences; rigid bodies in 6 DOF).
#include "fdem/fdem_world.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>

#include "contact/munjiza_potential.hpp"
#include "contact/tangential_spring.hpp"
#include "core/error.hpp"
#include "core/ticks.hpp"
#include "fdem/broad_phase.hpp"

namespace asperity::fdem {
namespace {

double tet_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).cross(c - a).dot(d - a) / 6.0;
}

// Mass, centre and inertia about the centre of a uniform tetrahedral mesh, exact:
// ∫ x xᵀ dV over a tetrahedron = V/20 (Σ xᵢxᵢᵀ + (Σxᵢ)(Σxᵢ)ᵀ) (Tonon 2004, eq. 2 in matrix form).
void mass_properties(const TetMesh& m, double density, double& mass, Vec3& centre, Mat3& inertia) {
  double vol = 0;
  Vec3 first = Vec3::Zero();
  for (Eigen::Index k = 0; k < m.tets.cols(); ++k) {
    const Vec3 a = m.nodes.col(m.tets(0, k)), b = m.nodes.col(m.tets(1, k)),
               c = m.nodes.col(m.tets(2, k)), d = m.nodes.col(m.tets(3, k));
    const double v = tet_volume(a, b, c, d);
    vol += v;
    first += v * 0.25 * (a + b + c + d);
  }
  centre = first / vol;
  Mat3 second = Mat3::Zero();
  for (Eigen::Index k = 0; k < m.tets.cols(); ++k) {
    Vec3 p[4];
    for (int i = 0; i < 4; ++i) p[i] = m.nodes.col(m.tets(i, k)) - centre;
    const double v = tet_volume(p[0], p[1], p[2], p[3]);
    const Vec3 s = p[0] + p[1] + p[2] + p[3];
    Mat3 acc = s * s.transpose();
    for (const Vec3& q : p) acc += q * q.transpose();
    second += v / 20.0 * acc;
  }
  mass = density * vol;
  inertia = density * (second.trace() * Mat3::Identity() - second);
}

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

bool needs_rebuild(const World& w) {
  const double limit = 0.25 * w.skin * w.skin;
  return ((w.x - w.x_at_build).colwise().squaredNorm().array() > limit).any();
}

contact::TetNodes gather(const World& w, int tet) {
  return {w.x.col(w.surface_tets(0, tet)), w.x.col(w.surface_tets(1, tet)),
          w.x.col(w.surface_tets(2, tet)), w.x.col(w.surface_tets(3, tet))};
}

bool boxes_overlap(const contact::TetNodes& a, const contact::TetNodes& b) {
  Vec3 alo = a[0], ahi = a[0], blo = b[0], bhi = b[0];
  for (int i = 1; i < 4; ++i) {
    alo = alo.cwiseMin(a[i]), ahi = ahi.cwiseMax(a[i]);
    blo = blo.cwiseMin(b[i]), bhi = bhi.cwiseMax(b[i]);
  }
  return !((alo.array() > bhi.array()).any() || (blo.array() > ahi.array()).any());
}

// Contact forces of every candidate pair into w.f, with friction, energy and the per-body output.
void contact_forces(World& w, double dt) {
  w.contact_energy = 0;
  w.contacts.reset(static_cast<int>(w.bodies.size()));
  w.penetration = 0;
  for (TetPair& p : w.pairs) {
    const contact::TetNodes a = gather(w, p.a), b = gather(w, p.b);
    if (!boxes_overlap(a, b)) {
      p.spring.setZero();
      continue;
    }
    ++w.contact_evaluations;
    const contact::PotentialPairForce c =
        contact::munjiza_potential(a, b, w.penalty, w.want_energy);
    if (!c.touching()) {
      p.spring.setZero();
      continue;
    }
    ++w.contacts_touching;
    const int ba = w.surface_tet_body[p.a], bb = w.surface_tet_body[p.b];
    if (const double r = c.depth / std::max(w.surface_tet_height[p.a], w.surface_tet_height[p.b]);
        r > w.penetration) {
      w.penetration = r;
      w.penetration_body_a = ba;
      w.penetration_body_b = bb;
    }
    std::array<Vec3, 4> on_a = c.on_a, on_b = c.on_b;
    const Vec3 fn = c.total_on_a();
    const double fn_mag = fn.norm();
    // Coulomb friction: a tangential spring with a Coulomb cap (contact/tangential_spring.hpp) at
    // the pressure centroid, stiffness the pair's secant normal stiffness |F_n| / depth (so the
    // tangential and normal penalty layers have the same compliance), acting on the relative
    // velocity of the two elements there; distributed by each element's barycentric coordinates.
    if (w.friction > 0 && fn_mag > 0 && c.depth > 0) {
      const Vec3 n = fn / fn_mag;
      const Eigen::Vector4d la = contact::barycentric(a, c.point),
                            lb = contact::barycentric(b, c.point);
      Vec3 va = Vec3::Zero(), vb = Vec3::Zero();
      for (int i = 0; i < 4; ++i) {
        va += la[i] * w.v.col(w.surface_tets(i, p.a));
        vb += lb[i] * w.v.col(w.surface_tets(i, p.b));
      }
      const Vec3 vr = va - vb;
      const Vec3 vt = vr - vr.dot(n) * n;
      const contact::TangentialForce ft = contact::tangential_spring(
          contact::rotate_into_tangent_plane(p.spring, n), vt, dt, fn_mag,
          {.stiffness = fn_mag / c.depth, .damping = 0, .friction = w.friction});
      p.spring = ft.spring;
      for (int i = 0; i < 4; ++i) {
        on_a[i] += la[i] * ft.force;
        on_b[i] -= lb[i] * ft.force;
      }
      w.contact_energy += ft.energy;
      w.dissipated += ft.dissipated;
    } else {
      p.spring.setZero();
    }
    Vec3 total_a = Vec3::Zero();
    for (int i = 0; i < 4; ++i) {
      w.f.col(w.surface_tets(i, p.a)) += on_a[i];
      w.f.col(w.surface_tets(i, p.b)) += on_b[i];
      total_a += on_a[i];
    }
    w.contact_energy += c.energy;
    w.contacts.add(ba, bb, total_a, fn, c.depth);
  }
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
  }
  if (w.want_energy) w.elastic_energy = elastic;
}

// Rigid bodies: total force and torque about the centre from their nodes' forces.
void reduce_rigid(World& w) {
  for (RigidBody& rb : w.rigid) {
    const Body& b = w.bodies[rb.body];
    rb.force.setZero();
    rb.torque.setZero();
    for (int i = b.node_begin; i < b.node_end; ++i) {
      rb.force += w.f.col(i);
      rb.torque += (w.x.col(i) - rb.centre).cross(w.f.col(i));
    }
  }
}

void compute_forces(World& w, double dt) {
  w.f.setZero();
  const std::uint64_t t0 = ticks();
  contact_forces(w, dt);
  const std::uint64_t t1 = ticks();
  internal_forces(w, dt);
  w.profile.contact += t1 - t0;
  w.profile.internal += ticks() - t1;
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

World make_world(const WorldDef& def) {
  World w;
  w.gravity = def.gravity;
  int n_nodes = 0;
  for (const BodyDef& b : def.bodies) n_nodes += static_cast<int>(b.mesh.nodes.cols());
  w.x.resize(3, n_nodes);
  w.v = Eigen::Matrix3Xd::Zero(3, n_nodes);
  w.f = Eigen::Matrix3Xd::Zero(3, n_nodes);
  w.mass.assign(n_nodes, 0.0);
  w.inv_mass.assign(n_nodes, 0.0);
  w.node_body.assign(n_nodes, -1);
  std::vector<int> st_nodes, st_body;
  std::vector<double> st_height;
  // Surface faces with their sub-tetrahedron height (centroid to face, 3V/(4A)), for the
  // contact time step.
  struct Face {
    int body;
    int nodes[3];
    double area, height;
  };
  std::vector<Face> faces;
  int offset = 0;
  double young_max = 0;
  for (std::size_t bi = 0; bi < def.bodies.size(); ++bi) {
    const BodyDef& d = def.bodies[bi];
    const std::string what = "body \"" + d.name + "\"";
    const int nn = static_cast<int>(d.mesh.nodes.cols());
    if (nn < 4 || d.mesh.tets.cols() == 0 || d.mesh.surface.cols() == 0) {
      throw InputError(what + ": mesh has no tetrahedra or no surface");
    }
    if (d.mesh.tets.minCoeff() < 0 || d.mesh.tets.maxCoeff() >= nn ||
        d.mesh.surface.minCoeff() < 0 || d.mesh.surface.maxCoeff() >= nn) {
      throw InputError(what + ": mesh refers to a node that does not exist");
    }
    Body body{.name = d.name, .kind = d.kind, .node_begin = offset, .node_end = offset + nn};
    // The penalty scales with the bodies that deform or move; a fixed block only supplies the
    // target (a stiff steel block must not shrink the step of a softer rock particle).
    if (d.kind != BodyKind::fixed) young_max = std::max(young_max, d.material.young);
    w.x.middleCols(offset, nn) = d.mesh.nodes;
    for (int i = offset; i < offset + nn; ++i) w.node_body[i] = static_cast<int>(bi);
    const Eigen::Matrix4Xi tets = d.mesh.tets.array() + offset;
    // Every body's elements give the lumped masses the contact time step uses (a rigid body's
    // too: constraining nodes to move rigidly only lowers the highest frequency).
    fem::TetElements e = fem::make_tet_elements(w.x, tets, d.material.young, d.material.poisson,
                                                d.material.density, 0.0, what);
    if (d.kind == BodyKind::deformable && d.damping_ratio > 0) {
      // ξ = β ω / 2 for stiffness-proportional damping, at the body's highest element frequency.
      e.damping = 2 * d.damping_ratio / fem::element_critical_step(e).omega_max;
    }
    std::vector<double> lumped(n_nodes, 0.0);
    fem::add_lumped_mass(e, lumped);
    Vec3 centre;
    Mat3 inertia;
    mass_properties(d.mesh, d.material.density, body.mass, centre, inertia);
    if (d.kind != BodyKind::fixed) {
      for (int i = offset; i < offset + nn; ++i) w.mass[i] = lumped[i];
    }
    if (d.kind == BodyKind::deformable) {
      for (int i = offset; i < offset + nn; ++i) {
        w.inv_mass[i] = 1.0 / w.mass[i];
        w.v.col(i) = d.velocity + d.angular_velocity.cross(w.x.col(i) - centre);
      }
      body.elements = static_cast<int>(w.elements.size());
      w.elements.push_back(std::move(e));
    } else if (d.kind == BodyKind::rigid) {
      RigidBody rb;
      rb.body = static_cast<int>(bi);
      rb.centre = rb.centre_initial = centre;
      rb.velocity = d.velocity;
      rb.omega = d.angular_velocity;
      rb.mass = body.mass;
      rb.inertia_body = inertia;
      rb.r_body = d.mesh.nodes.colwise() - centre;
      body.rigid = static_cast<int>(w.rigid.size());
      w.rigid.push_back(std::move(rb));
    }
    // Surface-adjacent tetrahedra: those with a node on the surface.
    std::vector<std::uint8_t> on_surface(nn, 0);
    for (Eigen::Index k = 0; k < d.mesh.surface.size(); ++k)
      on_surface[d.mesh.surface.data()[k]] = 1;
    std::map<std::array<int, 3>, int> face_tet;
    for (Eigen::Index k = 0; k < d.mesh.tets.cols(); ++k) {
      const auto t = d.mesh.tets.col(k);
      if (on_surface[t[0]] || on_surface[t[1]] || on_surface[t[2]] || on_surface[t[3]]) {
        for (int i = 0; i < 4; ++i) st_nodes.push_back(t[i] + offset);
        st_body.push_back(static_cast<int>(bi));
        // h_m = 3V/(4 A_m): the largest belongs to the smallest face.
        Vec3 p[4];
        for (int i = 0; i < 4; ++i) p[i] = d.mesh.nodes.col(t[i]);
        double a_min = 1e300;
        for (int skip = 0; skip < 4; ++skip) {
          const Vec3 &q0 = p[(skip + 1) % 4], &q1 = p[(skip + 2) % 4], &q2 = p[(skip + 3) % 4];
          a_min = std::min(a_min, 0.5 * (q1 - q0).cross(q2 - q0).norm());
        }
        st_height.push_back(0.75 * tet_volume(p[0], p[1], p[2], p[3]) / a_min);
      }
      for (int skip = 0; skip < 4; ++skip) {
        std::array<int, 3> key{};
        for (int i = 0, j = 0; i < 4; ++i) {
          if (i != skip) key[j++] = t[i];
        }
        std::sort(key.begin(), key.end());
        face_tet[key] = static_cast<int>(k);
      }
    }
    for (Eigen::Index k = 0; k < d.mesh.surface.cols(); ++k) {
      std::array<int, 3> key{d.mesh.surface(0, k), d.mesh.surface(1, k), d.mesh.surface(2, k)};
      std::sort(key.begin(), key.end());
      const auto it = face_tet.find(key);
      if (it == face_tet.end()) {
        throw InputError(what + ": surface triangle " + std::to_string(k) +
                         " is not a face of any tetrahedron");
      }
      const Vec3 a = d.mesh.nodes.col(d.mesh.surface(0, k)),
                 b = d.mesh.nodes.col(d.mesh.surface(1, k)),
                 c = d.mesh.nodes.col(d.mesh.surface(2, k));
      const double area = 0.5 * (b - a).cross(c - a).norm();
      const auto t = d.mesh.tets.col(it->second);
      const double v = tet_volume(d.mesh.nodes.col(t[0]), d.mesh.nodes.col(t[1]),
                                  d.mesh.nodes.col(t[2]), d.mesh.nodes.col(t[3]));
      faces.push_back({.body = static_cast<int>(bi),
                       .nodes = {key[0] + offset, key[1] + offset, key[2] + offset},
                       .area = area,
                       .height = 0.75 * v / area});
    }
    w.bodies.push_back(body);
    offset += nn;
  }
  w.surface_tets = Eigen::Map<const Eigen::Matrix4Xi>(st_nodes.data(), 4,
                                                      static_cast<Eigen::Index>(st_body.size()));
  w.surface_tet_body = std::move(st_body);
  w.surface_tet_height = std::move(st_height);
  if (young_max == 0) {
    for (const BodyDef& d : def.bodies) young_max = std::max(young_max, d.material.young);
  }
  w.penalty = def.contact.penalty > 0 ? def.contact.penalty : def.contact.alpha * young_max;
  w.friction = def.contact.friction;

  // Skin: half the mean sub-tetrahedron height of the moving bodies' surface faces. Rebuilds
  // happen every ~skin/(2 v dt) steps; the extra candidates cost one box test each per step.
  double hsum = 0;
  int hn = 0;
  for (const Face& f : faces) {
    if (w.bodies[f.body].kind != BodyKind::fixed) hsum += f.height, ++hn;
  }
  w.skin = hn > 0 ? 0.5 * hsum / hn : 0;
  w.face_nodes.resize(3, static_cast<Eigen::Index>(faces.size()));
  w.face_stiffness.resize(faces.size());
  std::vector<double> h_min(w.bodies.size(), 1e300);  // smallest height on any other body
  for (const Face& f : faces) {
    for (std::size_t b = 0; b < w.bodies.size(); ++b) {
      if (static_cast<int>(b) != f.body) h_min[b] = std::min(h_min[b], f.height);
    }
  }
  for (std::size_t k = 0; k < faces.size(); ++k) {
    const Face& f = faces[k];
    w.face_nodes.col(static_cast<Eigen::Index>(k)) << f.nodes[0], f.nodes[1], f.nodes[2];
    // Stiffness of the face pressed into another body: the overlap A·d sits in this face's
    // sub-tetrahedron and in the other body's, ∇φ = 1/height in each, so dF/dd = p A (1/h + 1/h').
    const double other = h_min[f.body] < 1e299 ? 1.0 / h_min[f.body] : 0.0;
    w.face_stiffness[k] = w.penalty * f.area * (1.0 / f.height + other);
  }

  w.x_initial = w.x;
  rebuild_pairs(w);
  compute_forces(w, 0.0);
  reduce_rigid(w);
  return w;
}

void step(World& w, double dt) {
  if (!w.failure.empty()) return;
  const std::uint64_t t0 = ticks();
  kick(w, 0.5 * dt);
  drift(w, dt);
  const std::uint64_t t1 = ticks();
  if (needs_rebuild(w)) rebuild_pairs(w);
  const std::uint64_t t2 = ticks();
  compute_forces(w, dt);  // contact, then internal forces, each timed
  const std::uint64_t t3 = ticks();
  reduce_rigid(w);
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
