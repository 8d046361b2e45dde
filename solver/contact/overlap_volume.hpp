// The overlap of two polyhedra, exactly, from their surfaces: the volume V = |A ∩ B|, its
// centroid, and the gradient of V under a rigid motion of either body, all from the parts of each
// body's surface triangles that lie inside the other body (a pure function of one triangle and
// one tetrahedron, summed over candidate pairs).
//
// Why the surface is enough. The boundary of A ∩ B is (∂A ∩ B) ∪ (∂B ∩ A). By the divergence
// theorem, with o any point and n the outward normal of the body whose surface it is,
//   V = 1/3 ∮_{∂(A∩B)} (x − o)·n dS,     ∫_{A∩B} x_i dV = 1/2 ∮ x_i² n_i dS.
// Translating A by dt changes the overlap only where ∂A lies inside B, by the swept volume:
//   dV = (∫_{∂A∩B} n dS) · dt =: S_A · dt,
// and rotating A by dθ about a point c moves x by dθ × (x − c):
//   dV = dθ · ∫_{∂A∩B} (x − c) × n dS =: dθ · M_A(c).
// S_A is the area vector of A's surface inside B; since ∮ n dS = 0 over the closed ∂(A∩B),
// S_A = −S_B: the area vector of the overlap's cross-section (for a sphere pressed into a plane,
// the contact disc, πa² along the normal). A force law F_A = −W'(V) S_A with torque
// −W'(V) M_A(c_A) is then exactly the gradient of an energy W(V): conservative, and its total
// torque vanishes (M_A(o) + M_B(o) = ∮ (x − o) × n dS = 0), so momentum and angular momentum are
// kept too (Feng 2021, "An energy-conserving contact theory for discrete element modelling of
// arbitrarily shaped particles", CMAME 373, 113454 and 113493).
//
// Bodies are tetrahedral meshes: B = ∪ T (disjoint interiors), so ∂A ∩ B is the sum over B's
// tetrahedra of ∂A ∩ T, and each piece is a surface triangle of A clipped by the four face planes
// of T (Sutherland–Hodgman; a triangle clipped by 4 planes has at most 7 vertices). Every integral
// above is at most quadratic over the clipped polygon, so a triangle fan integrates it exactly.
// This holds for non-convex bodies too (each tetrahedron is convex).
#pragma once

#include <array>

#include "solver/contact/munjiza_potential.hpp"
#include "solver/core/vec.hpp"

namespace asperity::contact {

// Surface integrals over the part of one body's surface inside the other, about the origin o
// given to the kernel (o near the contact keeps round-off small: the terms are |x − o| · area).
struct OverlapSide {
  double volume3 = 0;                   // ∫ (x − o)·n dS, m³ (three times its share of V)
  Vec3 area = Vec3::Zero();             // S = ∫ n dS, m²
  Vec3 moment = Vec3::Zero();           // ∫ (x − o) × n dS, m³
  Vec3 centroid_moment = Vec3::Zero();  // ½ ∫ (x − o)_i² n_i dS per i, m⁴
  double surface = 0;                   // ∫ dS, m² (area of this surface inside the other)

  OverlapSide& operator+=(const OverlapSide& s) {
    volume3 += s.volume3;
    area += s.area;
    moment += s.moment;
    centroid_moment += s.centroid_moment;
    surface += s.surface;
    return *this;
  }
};

using Triangle = std::array<Vec3, 3>;  // counter-clockwise seen from outside its body

// Adds the integrals over the part of triangle `tri` inside tetrahedron `tet` (positive volume)
// to `side`. Returns false when nothing of the triangle is inside.
bool clip_triangle_in_tet(const Triangle& tri, const TetNodes& tet, const Vec3& origin,
                          OverlapSide& side);

// The overlap of A and B from both sides' integrals (same origin).
struct Overlap {
  double volume = 0;             // V, m³
  Vec3 centroid = Vec3::Zero();  // m, valid when volume > 0
  Vec3 area = Vec3::Zero();      // S_A = −S_B: dV/d(translation of A), m²
};
Overlap combine(const OverlapSide& a, const OverlapSide& b, const Vec3& origin);

}  // namespace asperity::contact
