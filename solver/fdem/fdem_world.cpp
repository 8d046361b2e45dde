// FEM/DEM step: broad phase → contact (Munjiza potential + Coulomb friction) → internal forces
// (neo-Hookean tetrahedra) → integrate (central differences; rigid bodies in 6 DOF).
#include "solver/fdem/fdem_world.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <tuple>

#include "solver/contact/munjiza_potential.hpp"
#include "solver/contact/overlap_volume.hpp"
#include "solver/contact/tangential_spring.hpp"
#include "solver/contact/volume_hertz.hpp"
#include "solver/contact/volume_linear.hpp"
#include "solver/core/error.hpp"
#include "solver/core/ticks.hpp"
#include "solver/fdem/broad_phase.hpp"
#include "solver/fdem/time_step.hpp"

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

// Surface tetrahedron k's box in this contact pass (computed at its first pair).
const World::ContactBox& contact_tet_box(World& w, int k) {
  World::ContactBox& b = w.contact_boxes[static_cast<std::size_t>(k)];
  if (b.pass != w.contact_passes) {
    const contact::TetNodes x = gather(w, k);
    b.lo = b.hi = x[0];
    for (int i = 1; i < 4; ++i) b.lo = b.lo.cwiseMin(x[i]), b.hi = b.hi.cwiseMax(x[i]);
    b.pass = w.contact_passes;
  }
  return b;
}

// ... and its nodes and kernel frame (at its first pair whose boxes overlap).
const World::ContactTet& contact_tet(World& w, int k) {
  World::ContactTet& t = w.contact_tets[static_cast<std::size_t>(k)];
  if (t.frame_pass != w.contact_passes) {
    t.x = gather(w, k);
    t.frame = contact::tet_frame(t.x);
    t.frame_pass = w.contact_passes;
  }
  return t;
}

// Contact forces of every candidate pair into w.f, with friction, energy and the per-body output.
// Each surface tetrahedron's nodes, box and frame are computed once in the pass, at its first
// pair (contact_tet_box, contact_tet): the same numbers as pair by pair.
void contact_forces(World& w, double dt) {
  w.contact_energy = 0;
  w.contacts.reset(static_cast<int>(w.bodies.size()));
  w.penetration = 0;
  ++w.contact_passes;
  if (w.contact_tets.size() != static_cast<std::size_t>(w.surface_tets.cols())) {
    w.contact_tets.assign(static_cast<std::size_t>(w.surface_tets.cols()), {});
    w.contact_boxes.assign(static_cast<std::size_t>(w.surface_tets.cols()), {});
  }
  for (TetPair& p : w.pairs) {
    const World::ContactBox &ba_box = contact_tet_box(w, p.a), &bb_box = contact_tet_box(w, p.b);
    if ((ba_box.lo.array() > bb_box.hi.array()).any() ||
        (bb_box.lo.array() > ba_box.hi.array()).any()) {
      p.spring.setZero();
      continue;
    }
    ++w.contact_evaluations;
    const World::ContactTet &ta = contact_tet(w, p.a), &tb = contact_tet(w, p.b);
    const contact::TetNodes &a = ta.x, &b = tb.x;
    // The pair's penalty: the smaller of its two tetrahedra's where limit_face_penalty lowered
    // some (one p per pair keeps the pair force the gradient of one potential).
    const double penalty =
        w.tet_penalty_scale.empty()
            ? w.penalty
            : w.penalty * std::min(w.tet_penalty_scale[p.a], w.tet_penalty_scale[p.b]);
    const contact::PotentialPairForce c =
        contact::munjiza_potential(a, ta.frame, b, tb.frame, penalty, w.want_energy);
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

// A reference point of a body near its contacts: a moving body's centre, else its first node.
Vec3 reference_point(const World& w, int body) {
  const Body& b = w.bodies[body];
  if (b.kind == BodyKind::rigid) return w.rigid[b.rigid].centre;
  return w.x.col(b.node_begin);
}

BodyOverlap& overlap_of(World& w, std::vector<BodyOverlap>& now, int a, int b) {
  for (BodyOverlap& o : now) {
    if (o.a == a && o.b == b) return o;
  }
  BodyOverlap o{.a = a, .b = b};
  // The origin of the integrals: the moving body's centre (near the contact, unlike a plane's
  // far-away slab nodes), so the terms |x − o| · area stay of the size of the bodies.
  o.origin = reference_point(w, w.bodies[a].kind == BodyKind::fixed ? b : a);
  for (const BodyOverlap& old : w.overlaps) {
    if (old.a == a && old.b == b) {
      o.energy = old.energy, o.volume = old.volume, o.slope = old.slope, o.spring = old.spring;
    }
  }
  now.push_back(o);
  return now.back();
}

// Clips the surface triangles owned by tetrahedron `owner` against tetrahedron `target` into
// `side`.
void clip_owned_faces(const World& w, int owner, const contact::TetNodes& target,
                      const Vec3& origin, contact::OverlapSide& side) {
  for (int k = w.tet_faces_begin[owner]; k < w.tet_faces_begin[owner + 1]; ++k) {
    const auto f = w.face_outward.col(w.tet_faces[k]);
    contact::clip_triangle_in_tet({w.x.col(f[0]), w.x.col(f[1]), w.x.col(f[2])}, target, origin,
                                  side);
  }
}

// A body's velocity at point x, m/s (zero for a fixed body).
Vec3 velocity_at(const World& w, int body, const Vec3& x) {
  const Body& b = w.bodies[body];
  if (b.kind != BodyKind::rigid) return Vec3::Zero();
  const RigidBody& rb = w.rigid[b.rigid];
  return rb.velocity + rb.omega.cross(x - rb.centre);
}

// Volume laws' Coulomb friction on body a of the overlap `o` (N), its spring carried in o: the
// tangential spring k_t with the cap μ |F_n| (contact/tangential_spring.hpp) on the slip of a
// against b at the overlap's centroid; its stored energy joins the contact energy and its sliding
// work the dissipated energy. Zero without friction. k_t: volume-linear's `contact.kt`;
// volume-hertz's Mindlin stiffness from the overlap (contact::volume_hertz_tangent_stiffness),
// unbounded at a face's first touch like its normal one, so a face that lands slides at once.
Vec3 volume_friction(World& w, BodyOverlap& o, const Vec3& point, const Vec3& normal_force_a,
                     double area, double volume, double dt) {
  const double fn = normal_force_a.norm();
  if (!(w.friction > 0) || !(fn > 0)) {
    o.spring.setZero();
    return Vec3::Zero();
  }
  double kt = w.kt;
  if (w.law == ContactLaw::volume_hertz) {
    const Material &ma = w.bodies[o.a].material, &mb = w.bodies[o.b].material;
    kt = contact::volume_hertz_tangent_stiffness(fn, area, volume, effective_shear(ma, mb),
                                                 effective_young(ma, mb));
  }
  const Vec3 n = normal_force_a / fn;
  const Vec3 vr = velocity_at(w, o.a, point) - velocity_at(w, o.b, point);
  const contact::TangentialForce ft = contact::tangential_spring(
      contact::rotate_into_tangent_plane(o.spring, n), vr - vr.dot(n) * n, dt, fn,
      {.stiffness = kt, .damping = 0, .friction = w.friction});
  o.spring = ft.spring;
  w.contact_energy += ft.energy;
  w.dissipated += ft.dissipated;
  return ft.force;
}

// Volume laws: every candidate pair of tetrahedra adds its clipped surface integrals to its body
// pair; each body pair in contact then gets F_A = −s S_A with s = W'(V) (volume-hertz) or
// k_v V / |S_A| (volume-linear), and the torque −s M_A about A's centre (volume-hertz: the exact
// gradient) or that of F_A at the overlap's centroid (volume-linear, as YADE applies it)
// (contact/overlap_volume.hpp). With friction, a tangential spring k_t and a Coulomb cap μ |F_n|
// at the overlap's centroid (contact/tangential_spring.hpp), on the relative velocity of the two
// bodies there: the friction of YADE's Law2_PolyhedraGeom_PolyhedraPhys_Volumetric (its ks,
// its shear increment from the relative velocity at the contact point, its cap); volume-hertz
// takes Mindlin's k_t (volume_friction).
void volume_contact_forces(World& w, double dt) {
  w.contact_energy = 0;
  w.contacts.reset(static_cast<int>(w.bodies.size()));
  w.penetration = 0;
  for (RigidBody& rb : w.rigid) rb.volume_force.setZero(), rb.volume_torque.setZero();
  std::vector<BodyOverlap> now;
  for (const TetPair& p : w.pairs) {
    const contact::TetNodes a = gather(w, p.a), b = gather(w, p.b);
    if (!boxes_overlap(a, b)) continue;
    ++w.contact_evaluations;
    int ba = w.surface_tet_body[p.a], bb = w.surface_tet_body[p.b];
    int ta = p.a, tb = p.b;
    if (ba > bb) std::swap(ba, bb), std::swap(ta, tb);
    BodyOverlap& o = overlap_of(w, now, ba, bb);
    clip_owned_faces(w, ta, ta == p.a ? b : a, o.origin, o.side_a);
    clip_owned_faces(w, tb, tb == p.b ? a : b, o.origin, o.side_b);
  }
  for (BodyOverlap& o : now) {
    const contact::Overlap ov = contact::combine(o.side_a, o.side_b, o.origin);
    const double area = ov.area.norm();
    if (!(ov.volume > 0) || !(area > 0)) {
      o.energy = 0, o.volume = 0, o.slope = 0, o.spring.setZero();
      continue;
    }
    ++w.contacts_touching;
    const Body &body_a = w.bodies[o.a], &body_b = w.bodies[o.b];
    double slope = 0;
    if (w.law == ContactLaw::volume_hertz) {
      const double c = contact::volume_hertz_coefficient(
          effective_young(body_a.material, body_b.material),
          contact::volume_hertz_radius(body_a.radius, body_b.radius));
      const contact::VolumeEnergy e = contact::volume_hertz(ov.volume, c);
      slope = e.slope;
      o.energy = e.energy;
    } else {
      slope = w.kv * ov.volume / area;  // |F| = k_v V (contact/volume_linear.hpp)
      // The force is −s ∇V, so its work is ∫ s dV along any path: trapezoidal in V.
      o.energy += 0.5 * (slope + o.slope) * (ov.volume - o.volume);
    }
    o.volume = ov.volume;
    o.slope = slope;
    const Vec3 force_a = -slope * o.side_a.area;
    const Vec3 force_b = -slope * o.side_b.area;
    const Vec3 friction_a = volume_friction(w, o, ov.centroid, force_a, area, ov.volume, dt);
    for (const auto& [body, side, force, tangential] :
         {std::tuple{o.a, &o.side_a, force_a, friction_a},
          std::tuple{o.b, &o.side_b, force_b, Vec3(-friction_a)}}) {
      const Body& bd = w.bodies[body];
      if (bd.kind != BodyKind::rigid) continue;
      RigidBody& rb = w.rigid[bd.rigid];
      rb.volume_force += force + tangential;
      rb.volume_torque += (ov.centroid - rb.centre).cross(tangential);
      if (w.law == ContactLaw::volume_hertz) {
        // The gradient of W under rotation: −W' M(c), M(c) = M(o) − (c − o) × S.
        rb.volume_torque -= slope * (side->moment - (rb.centre - o.origin).cross(side->area));
      } else {
        // YADE's volumetric law applies the force at the overlap's centroid.
        rb.volume_torque += (ov.centroid - rb.centre).cross(force);
      }
    }
    w.contact_energy += o.energy;
    // The overlap's mean depth V/|S| (m) is its signed overlap: linear in the approach for a
    // sphere, a vertex, an edge and a face alike, so the contact's start and end interpolate well.
    w.contacts.add(o.a, o.b, Vec3(force_a + friction_a), force_a, ov.volume / area);
  }
  w.overlaps = std::move(now);
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
    contact_forces(w, dt);
  } else {
    volume_contact_forces(w, dt);
  }
  if (w.keep_contact_force) w.f_contact = w.f;  // f held the contact forces only, so far
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

// make_world's phases, in the order it calls them.

// Surface faces with their sub-tetrahedron height (centroid to face, 3V/(4A)), for the
// contact time step.
struct Face {
  int body;
  int nodes[3];     // sorted
  int oriented[3];  // as the surface lists it (outward)
  double area, height;
};

// What make_world gathers body by body before it moves it into the world.
struct SurfaceLists {
  std::vector<int> tet_nodes, tet_body;  // surface-adjacent tetrahedra (global nodes), owner
  std::vector<double> tet_height;        // largest sub-tetrahedron height of each
  std::vector<Face> faces;
  std::vector<int> face_owner;   // per face: its tetrahedron among the contact tetrahedra
  std::vector<int> contact_tet;  // the current body's tetrahedra → contact tetrahedron (or −1)
};

void allocate_nodes(World& w, const WorldDef& def) {
  int n_nodes = 0;
  for (const BodyDef& b : def.bodies) n_nodes += static_cast<int>(b.mesh.nodes.cols());
  w.x.resize(3, n_nodes);
  w.v = Eigen::Matrix3Xd::Zero(3, n_nodes);
  w.f = Eigen::Matrix3Xd::Zero(3, n_nodes);
  w.mass.assign(n_nodes, 0.0);
  w.inv_mass.assign(n_nodes, 0.0);
  w.node_body.assign(n_nodes, -1);
}

void check_mesh(const BodyDef& d, const std::string& what) {
  const int nn = static_cast<int>(d.mesh.nodes.cols());
  if (nn < 4 || d.mesh.tets.cols() == 0 || d.mesh.surface.cols() == 0) {
    throw InputError(what + ": mesh has no tetrahedra or no surface");
  }
  if (d.mesh.tets.minCoeff() < 0 || d.mesh.tets.maxCoeff() >= nn || d.mesh.surface.minCoeff() < 0 ||
      d.mesh.surface.maxCoeff() >= nn) {
    throw InputError(what + ": mesh refers to a node that does not exist");
  }
}

// Bodies and masses: the body's nodes at `offset`, their lumped masses, and its elements
// (deformable) or its rigid state (rigid).
Body add_body(World& w, const BodyDef& d, int bi, int offset, const std::string& what) {
  const int nn = static_cast<int>(d.mesh.nodes.cols());
  Body body{.name = d.name,
            .kind = d.kind,
            .node_begin = offset,
            .node_end = offset + nn,
            .material = d.material};
  w.x.middleCols(offset, nn) = d.mesh.nodes;
  for (int i = offset; i < offset + nn; ++i) w.node_body[i] = bi;
  const Eigen::Matrix4Xi tets = d.mesh.tets.array() + offset;
  // Every body's elements give the lumped masses the contact time step uses (a rigid body's
  // too: constraining nodes to move rigidly only lowers the highest frequency).
  fem::TetElements e = fem::make_tet_elements(w.x, tets, d.material.young, d.material.poisson,
                                              d.material.density, 0.0, what);
  // The law is the deformable body's; a rigid or fixed body's elements only give masses and steps,
  // which are the same for both laws (the linear law's stiffness is the neo-Hookean one at F = I).
  if (d.kind == BodyKind::deformable) e.law = d.material.law;
  if (d.kind == BodyKind::deformable && d.damping_ratio > 0) {
    // ξ = β ω / 2 for stiffness-proportional damping, at the body's highest element frequency.
    e.damping = 2 * d.damping_ratio / fem::element_critical_step(e).omega_max;
  }
  std::vector<double> lumped(static_cast<std::size_t>(w.node_count()), 0.0);
  fem::add_lumped_mass(e, lumped);
  Vec3 centre;
  Mat3 inertia;
  mass_properties(d.mesh, d.material.density, body.mass, centre, inertia);
  body.radius = d.kind == BodyKind::fixed
                    ? std::numeric_limits<double>::infinity()
                    : contact::equivalent_radius(body.mass / d.material.density);
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
    rb.body = bi;
    rb.centre = rb.centre_initial = centre;
    rb.velocity = d.velocity;
    rb.omega = d.angular_velocity;
    rb.mass = body.mass;
    rb.inertia_body = inertia;
    rb.r_body = d.mesh.nodes.colwise() - centre;
    body.rigid = static_cast<int>(w.rigid.size());
    w.rigid.push_back(std::move(rb));
  }
  return body;
}

// Contact tetrahedra: those with a node on the surface (every tetrahedron under a volume law,
// whose overlap integrals clip the surface triangles they own), with their largest
// sub-tetrahedron height.
void add_surface_tets(SurfaceLists& s, const BodyDef& d, int bi, int offset, bool volume_law) {
  s.contact_tet.assign(static_cast<std::size_t>(d.mesh.tets.cols()), -1);
  std::vector<std::uint8_t> on_surface(static_cast<std::size_t>(d.mesh.nodes.cols()), 0);
  for (Eigen::Index k = 0; k < d.mesh.surface.size(); ++k) on_surface[d.mesh.surface.data()[k]] = 1;
  for (Eigen::Index k = 0; k < d.mesh.tets.cols(); ++k) {
    const auto t = d.mesh.tets.col(k);
    if (!(volume_law || on_surface[t[0]] || on_surface[t[1]] || on_surface[t[2]] ||
          on_surface[t[3]])) {
      continue;
    }
    s.contact_tet[static_cast<std::size_t>(k)] = static_cast<int>(s.tet_body.size());
    for (int i = 0; i < 4; ++i) s.tet_nodes.push_back(t[i] + offset);
    s.tet_body.push_back(bi);
    // h_m = 3V/(4 A_m): the largest belongs to the smallest face.
    Vec3 p[4];
    for (int i = 0; i < 4; ++i) p[i] = d.mesh.nodes.col(t[i]);
    double a_min = 1e300;
    for (int skip = 0; skip < 4; ++skip) {
      const Vec3 &q0 = p[(skip + 1) % 4], &q1 = p[(skip + 2) % 4], &q2 = p[(skip + 3) % 4];
      a_min = std::min(a_min, 0.5 * (q1 - q0).cross(q2 - q0).norm());
    }
    s.tet_height.push_back(0.75 * tet_volume(p[0], p[1], p[2], p[3]) / a_min);
  }
}

// Surface faces: each surface triangle with the tetrahedron it bounds (its area and
// sub-tetrahedron height); a triangle that bounds none is an input error.
void add_surface_faces(SurfaceLists& s, const BodyDef& d, int bi, int offset,
                       const std::string& what) {
  std::map<std::array<int, 3>, int> face_tet;
  for (Eigen::Index k = 0; k < d.mesh.tets.cols(); ++k) {
    const auto t = d.mesh.tets.col(k);
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
    s.face_owner.push_back(s.contact_tet[static_cast<std::size_t>(it->second)]);
    s.faces.push_back({.body = bi,
                       .nodes = {key[0] + offset, key[1] + offset, key[2] + offset},
                       .oriented = {d.mesh.surface(0, k) + offset, d.mesh.surface(1, k) + offset,
                                    d.mesh.surface(2, k) + offset},
                       .area = area,
                       .height = 0.75 * v / area});
  }
}

// Penalty p (Pa): given, or α times the largest Young's modulus of the bodies that deform or
// move; a fixed block only supplies the target (a stiff steel block must not shrink the step of
// a softer rock particle). With no moving body, the largest of all.
double contact_penalty(const WorldDef& def) {
  if (def.contact.penalty > 0) return def.contact.penalty;
  double young_max = 0;
  for (const BodyDef& d : def.bodies) {
    if (d.kind != BodyKind::fixed) young_max = std::max(young_max, d.material.young);
  }
  if (young_max == 0) {
    for (const BodyDef& d : def.bodies) young_max = std::max(young_max, d.material.young);
  }
  return def.contact.alpha * young_max;
}

// Skin: half the mean sub-tetrahedron height of the moving bodies' surface faces. Rebuilds
// happen every ~skin/(2 v dt) steps; the extra candidates cost one box test each per step.
double contact_skin(const World& w, const std::vector<Face>& faces) {
  double hsum = 0;
  int hn = 0;
  for (const Face& f : faces) {
    if (w.bodies[f.body].kind != BodyKind::fixed) hsum += f.height, ++hn;
  }
  return hn > 0 ? 0.5 * hsum / hn : 0;
}

void set_face_stiffness(World& w, const std::vector<Face>& faces) {
  w.face_nodes.resize(3, static_cast<Eigen::Index>(faces.size()));
  w.face_outward.resize(3, static_cast<Eigen::Index>(faces.size()));
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
    w.face_outward.col(static_cast<Eigen::Index>(k)) << f.oriented[0], f.oriented[1], f.oriented[2];
    // Stiffness of the face pressed into another body: the overlap A·d sits in this face's
    // sub-tetrahedron and in the other body's, ∇φ = 1/height in each, so dF/dd = p A (1/h + 1/h').
    const double other = h_min[f.body] < 1e299 ? 1.0 / h_min[f.body] : 0.0;
    w.face_stiffness[k] = w.penalty * f.area * (1.0 / f.height + other);
  }
}

// Surface triangles by owning contact tetrahedron (CSR), for the volume laws' clipping.
void index_faces_by_tet(World& w, const std::vector<int>& face_owner) {
  w.tet_faces_begin.assign(w.surface_tet_body.size() + 1, 0);
  for (const int t : face_owner) {
    if (t >= 0) ++w.tet_faces_begin[static_cast<std::size_t>(t) + 1];
  }
  for (std::size_t k = 1; k < w.tet_faces_begin.size(); ++k) {
    w.tet_faces_begin[k] += w.tet_faces_begin[k - 1];
  }
  w.tet_faces.resize(static_cast<std::size_t>(w.tet_faces_begin.back()));
  std::vector<int> fill(w.tet_faces_begin.begin(), w.tet_faces_begin.end() - 1);
  for (std::size_t f = 0; f < face_owner.size(); ++f) {
    const int t = face_owner[f];
    if (t >= 0)
      w.tet_faces[static_cast<std::size_t>(fill[static_cast<std::size_t>(t)]++)] =
          static_cast<int>(f);
  }
}

}  // namespace

// Bodies and masses → surface tetrahedra and faces → penalty and face stiffness → skin → the
// first candidate pairs and forces.
World make_world(const WorldDef& def) {
  World w;
  w.gravity = def.gravity;
  allocate_nodes(w, def);
  SurfaceLists surface;
  int offset = 0;
  const bool volume_law = def.contact.law != ContactLaw::potential;
  for (std::size_t bi = 0; bi < def.bodies.size(); ++bi) {
    const BodyDef& d = def.bodies[bi];
    const std::string what = "body \"" + d.name + "\"";
    const int body = static_cast<int>(bi);
    check_mesh(d, what);
    if (volume_law && d.kind == BodyKind::deformable) {
      throw InputError(what + ": the volume contact laws are for rigid and fixed bodies only");
    }
    w.bodies.push_back(add_body(w, d, body, offset, what));
    add_surface_tets(surface, d, body, offset, volume_law);
    add_surface_faces(surface, d, body, offset, what);
    offset += static_cast<int>(d.mesh.nodes.cols());
  }
  w.surface_tets = Eigen::Map<const Eigen::Matrix4Xi>(
      surface.tet_nodes.data(), 4, static_cast<Eigen::Index>(surface.tet_body.size()));
  w.surface_tet_body = std::move(surface.tet_body);
  w.surface_tet_height = std::move(surface.tet_height);
  w.penalty = contact_penalty(def);
  w.friction = def.contact.friction;
  w.law = def.contact.law;
  w.kv = def.contact.kv;
  w.kt = def.contact.kt;
  if (w.law == ContactLaw::volume_linear && !(w.kv > 0)) {
    throw InputError("contact: volume-linear needs a stiffness kv > 0 (N/m³)");
  }
  index_faces_by_tet(w, surface.face_owner);
  w.skin = contact_skin(w, surface.faces);
  set_face_stiffness(w, surface.faces);
  w.penalty_asked = w.penalty;
  if (w.law == ContactLaw::potential && def.contact.max_contact_factor > 0) {
    switch (def.contact.contact_step_fix) {
      case ContactStepFix::penalty:
        limit_penalty(w, def.contact.max_contact_factor);
        break;
      case ContactStepFix::face_penalty:
        limit_face_penalty(w, def.contact.max_contact_factor);
        break;
      case ContactStepFix::mass:
        scale_contact_mass(w, def.contact.max_contact_factor);
        break;
    }
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
