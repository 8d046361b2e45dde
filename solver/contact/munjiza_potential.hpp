// Munjiza's distributed-potential contact between two linear tetrahedra of different bodies
// (Munjiza 2004, The Combined Finite-Discrete Element Method, §2.5–2.6, eqs 2.35–2.55): a pure
// function of the two elements' node positions and the penalty.
//
// Potential. Each tetrahedron is split about its centroid into four sub-tetrahedra, one per face;
// in the sub-tetrahedron of the face opposite node m the potential is the volume ratio
// V(face, p) / V(face, centroid) (eq. 2.36). In the element's barycentric coordinates L₀..L₃ that
// ratio is 4 L_m, and p lies in that sub-tetrahedron exactly when L_m is the smallest, so
//   φ(p) = 4 min_m L_m(p)   inside the element (0 on its faces, 1 at its centroid).
// φ is linear in each sub-tetrahedron, and invariant under affine maps, so it moves with the
// deforming element.
//
// Force. With penalty p (Pa) the force on tetrahedron a is (eqs 2.37–2.38)
//   f_a = p ∫_{a∩b} (∇φ_a − ∇φ_b) dV = −f_b,
// the gradient of U = p ∫_{a∩b} (φ_a + φ_b) dV under a rigid translation of a. Because φ_b = 0
// on b's faces, the divergence theorem turns the φ_b part into a surface integral over a's faces
// inside b: p ∫_{a∩b} ∇φ_b dV = p Σ_faces ∫_{face∩b} φ_b n dS (n the face's outward normal),
// and likewise for φ_a. So, as Munjiza does (eqs 2.50–2.55), each face of one element is clipped
// (Sutherland–Hodgman) against each sub-tetrahedron of the other; on the clipped polygon φ is
// linear and the traction −p φ n is integrated exactly (quadratic integrands on a triangle fan,
// ∫ f g dA = A/12 (Σ fᵢgᵢ + Σfᵢ Σgᵢ)). The traction goes to the face's three nodes by their
// linear shape functions and, reversed, to the other element's four nodes by its barycentric
// coordinates (Munjiza's distribution to the sub-tetrahedron's nodes, the centroid's share split
// equally, is the same thing). The pair is processed twice, each element once as contactor.
// Forces on the two elements are equal and opposite to round-off, and the work they do equals the
// change of U for any rigid motion; for deforming elements the mismatch is p ∫ φ div v dV, of the
// order of the strain rate times the stored energy.
//
// Energy (when asked): p ∫_{a∩b∩T_m} φ dV = p/(2|g_m|²) ∮ φ² g_m·n dS (the field φ² g/(2|g|²)
// has divergence φ when ∇φ = g is constant), over the polyhedron's faces: the clipped faces above
// and the other element's internal sub-tetrahedron faces clipped against this one (φ = 0 on its
// outer faces).
#pragma once

#include <array>

#include <Eigen/Core>

#include "solver/core/vec.hpp"

namespace asperity::contact {

using TetNodes = std::array<Vec3, 4>;  // positive volume: ((x1−x0)×(x2−x0))·(x3−x0) > 0

struct PotentialPairForce {
  std::array<Vec3, 4> on_a{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};  // N
  std::array<Vec3, 4> on_b{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};  // N
  double energy = 0;  // J, p ∫ (φ_a + φ_b) dV over the overlap (only when asked)
  // Deepest point of either element's faces inside the other, measured from the other's face
  // through its sub-tetrahedron (L_m / |∇L_m|), m; 0 when apart.
  double depth = 0;
  // Pressure centroid: ∫ φ x dS / ∫ φ dS over the clipped faces of both passes (m), where a
  // tangential force acts; weight = ∫ φ dS (m²), 0 when apart.
  Vec3 point = Vec3::Zero();
  double weight = 0;

  bool touching() const { return weight > 0; }
  Vec3 total_on_a() const { return on_a[0] + on_a[1] + on_a[2] + on_a[3]; }
};

// What the kernel needs of each element besides its nodes: its barycentric map
// L_{1..3} = B (x − x₀), L₀ = 1 − ΣL, and the gradients of L₀..L₃. A function of the element's
// current nodes only, so a caller that meets one element in several pairs within a step (a
// block's large tetrahedra meet hundreds) computes it once (fdem/potential_contact.cpp).
struct TetFrame {
  Vec3 origin;
  Mat3 b;
  Vec3 grad[4];
};
TetFrame tet_frame(const TetNodes& t);

// L₀..L₃ of x into l.
inline void coords(const TetFrame& m, const Vec3& x, double* l) {
  const Vec3 r = m.b * (x - m.origin);
  l[1] = r.x(), l[2] = r.y(), l[3] = r.z();
  l[0] = 1.0 - r.x() - r.y() - r.z();
}

// penalty: p, Pa. Both elements must have positive volume.
PotentialPairForce munjiza_potential(const TetNodes& a, const TetNodes& b, double penalty,
                                     bool with_energy);
// The same with the elements' frames given (each tet_frame of its nodes): the same result.
PotentialPairForce munjiza_potential(const TetNodes& a, const TetFrame& fa, const TetNodes& b,
                                     const TetFrame& fb, double penalty, bool with_energy);

// Barycentric coordinates (L₀..L₃) of x in a tetrahedron (extended linearly outside it).
Eigen::Vector4d barycentric(const TetNodes& t, const Vec3& x);

}  // namespace asperity::contact
