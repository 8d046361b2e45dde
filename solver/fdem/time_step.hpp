// Predicted critical time step of an FEM/DEM world: element limit and penalty-contact limit.
#pragma once

#include <string>
#include <vector>

#include "solver/fdem/fdem_world.hpp"

namespace asperity::fdem {

struct CriticalStep {
  double element = 0;        // s, damped element-only bound of the stiffest body (no contact)
  double contact = 0;        // s, 2/ω_c of the stiffest penalty contact alone
  double critical = 0;       // s, the step of elements and contacts together (below)
  std::string limited_by;    // "element" or "contact", the smaller of the two parts
  std::string element_body;  // the body with the stiffest elements
};

// Contact model. Every surface face of a moving body, pressed into another body, adds a
// stiffness k_f = p A (1/h + 1/h') (build_world.cpp, set_face_stiffness) spread over its three
// nodes by the consistent face matrix K_f = k_f/12 [[2,1,1],[1,2,1],[1,1,2]] ⊗ I (≥ the normal-only
// spring), taken as a spring to the ground (the partner's compliance is in 1/h'), so the bodies
// decouple and the world's largest ω is the largest over its bodies.
//
// Deformable body: every surface face is assumed pressed at once (the step is fixed for the
// run). Its K_f joins the stiffness of the element that owns the face, and the element bound
// with a mass split (fem::element_critical_step) bounds ω of K_elements + Σ K_f as a whole;
// Weyl's λ_max(A + B) ≤ λ_max(A) + λ_max(B) with a Gershgorin nodal bound on M⁻¹K_c,
// ω² ≤ ω_e² + max_nodes Σ_faces (k_f/3)/m_node, is rigorous too and the smaller of the two is
// taken (the first is 20–30 % tighter in ω: tests/fem/test_element_step.cpp). The damping
// correction (2/ω)(√(1+ξ²) − ξ) takes ξ = βω/2 at the combined ω (more damping than the
// contact part has, so conservative). Finite-strain stiffening of the neo-Hookean law in
// compression is left to the safety factor. The penalty p = αE makes ω_c about √α times ω_e.
//
// Rigid body: the same face springs seen through its 6 DOF, u(x) = t + θ × (x − c), so
// K_r = Σ_f κ_f ∫_{P_f} G(x)ᵀ G(x) dA with G(x) = [I, −[x − c]×], κ_f = k_f/A_f, M_r =
// diag(m I, I_c), and ω² the largest root of det(K_r − ω² M_r) = 0. A rigid body cannot press its
// whole surface at once (counting every face made the bound 10× conservative, 50× on a vertex
// impact), so P_f is the part of face f that can be pressed (rigid_contact_faces): beyond the
// target plane at the deepest penetration δ_max the energy allows. The penalty force grows with
// the pressed area, so the tangent stiffness is largest there, and central differences stay
// stable while dt ω_t ≤ 2 for the largest tangent ω_t over the motion (Belytschko, Liu & Moran
// 2000, §6.3). In the fallback P_f is the whole face, where the integral is the consistent face
// matrix above.
CriticalStep critical_step(const World& world);

// The surface faces (indices into World::face_nodes) of rigid body `rigid` (index into
// World::rigid) that can be pressed in this scene, with the largest penetration δ_max (m) along
// the approach direction n, or depth < 0 and every face of the body (the fallback).
//
// Approach bound. When the body is the only moving one, does not spin, and moves along one line
// n (its velocity v, with gravity g zero or along v: a drop or a throw onto a target), and the
// fixed bodies lie ahead of it with a flat face normal to n under every point that can touch,
// the body can penetrate that face by at most δ_max, the root of the energy balance
//   U_a(δ) = ½ m |v|² + m (g·n) (gap + δ),
// gap the clearance from the support point (the body's extreme point along n) to the target
// plane, U_a(δ) = p ∫ φ_a dV over the body's part beyond the plane after a translation δ + gap
// along n: the body's own share of the stored penalty energy U = p ∫ (φ_a + φ_b) dV
// (contact/munjiza_potential.hpp), computed exactly by clipping each sub-tetrahedron of the
// surface-adjacent elements (φ_a linear there). U_a ≤ U and it grows with δ, so δ_max bounds the
// penetration the energy allows. Assumptions: the body does not rotate appreciably during the
// impact (a rotation is paid from the same energy but could bring other faces down) and the
// target stays flat over the pressed patch; stability gate stability-rigid-particle-block checks
// the result against the measured limit. Otherwise (other moving bodies, spin, gravity across v,
// no flat target face ahead, or no root short of burying the body) every face counts.
struct ContactFaces {
  std::vector<int> faces;      // the faces with a point within δ_max of the support point
  double depth = -1;           // m, δ_max, or < 0 for the fallback
  Vec3 normal = Vec3::Zero();  // n, the approach direction
  double support = 0;          // m, the support point's position along n
};
ContactFaces rigid_contact_faces(const World& world, int rigid);

}  // namespace asperity::fdem
