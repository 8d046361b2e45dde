// The potential law's contact pass (Munjiza's distributed potential between surface tetrahedra,
// contact/munjiza_potential.hpp) with its Coulomb friction (contact/potential_friction.hpp).
#include <algorithm>
#include <array>

#include "solver/contact/munjiza_potential.hpp"
#include "solver/contact/potential_friction.hpp"
#include "solver/fdem/world_phases.hpp"

namespace asperity::fdem::detail {
namespace {

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

}  // namespace

// Contact forces of every candidate pair into w.f, with friction, energy and the per-body output.
// Each surface tetrahedron's nodes, box and frame are computed once in the pass, at its first
// pair (contact_tet_box, contact_tet): the same numbers as pair by pair.
void potential_contact_forces(World& w, double dt) {
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
    // Coulomb friction at the pressure centroid (contact/potential_friction.hpp).
    if (w.friction > 0 && fn_mag > 0 && c.depth > 0) {
      std::array<Vec3, 4> va, vb;
      for (int i = 0; i < 4; ++i) {
        va[i] = w.v.col(w.surface_tets(i, p.a));
        vb[i] = w.v.col(w.surface_tets(i, p.b));
      }
      const contact::PotentialFriction ft =
          contact::potential_friction(a, b, va, vb, c.point, fn, c.depth, p.spring, dt, w.friction);
      p.spring = ft.tangential.spring;
      for (int i = 0; i < 4; ++i) {
        on_a[i] += ft.on_a[i];
        on_b[i] -= ft.on_b[i];
      }
      w.contact_energy += ft.tangential.energy;
      w.dissipated += ft.tangential.dissipated;
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

}  // namespace asperity::fdem::detail
