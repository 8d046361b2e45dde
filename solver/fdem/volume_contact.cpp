// The volume laws' contact pass (volume-hertz, volume-linear) between rigid and fixed polyhedra:
// the overlap integrals of each body pair (contact/overlap_volume.hpp), its force and torque, and
// its friction (contact/tangential_spring.hpp).
#include <algorithm>
#include <tuple>
#include <vector>

#include "solver/contact/overlap_volume.hpp"
#include "solver/contact/tangential_spring.hpp"
#include "solver/contact/volume_hertz.hpp"
#include "solver/contact/volume_linear.hpp"
#include "solver/fdem/world_phases.hpp"

namespace asperity::fdem::detail {
namespace {

bool boxes_overlap(const contact::TetNodes& a, const contact::TetNodes& b) {
  Vec3 alo = a[0], ahi = a[0], blo = b[0], bhi = b[0];
  for (int i = 1; i < 4; ++i) {
    alo = alo.cwiseMin(a[i]), ahi = ahi.cwiseMax(a[i]);
    blo = blo.cwiseMin(b[i]), bhi = bhi.cwiseMax(b[i]);
  }
  return !((alo.array() > bhi.array()).any() || (blo.array() > ahi.array()).any());
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

}  // namespace

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

}  // namespace asperity::fdem::detail
