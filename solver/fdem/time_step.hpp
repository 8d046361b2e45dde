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
// stiffness k_f = p A (1/h + 1/h') (fdem_world.cpp) spread over its three nodes by the consistent
// face matrix K_f = k_f/12 [[2,1,1],[1,2,1],[1,1,2]] ⊗ I (≥ the normal-only spring), taken as a
// spring to the ground (the partner's compliance is in 1/h'), so the bodies decouple and the
// world's largest ω is the largest over its bodies.
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

// Lowers the penalty of a potential-law world, where needed, so that the penalty contact pulls no
// deformable body's predicted step (critical_step) more than `factor` below its elements' own
// limit: returns the scale s ≤ 1 applied to World::penalty and World::face_stiffness (1: nothing
// changed; World::penalty_asked keeps the penalty asked for).
//
// Why (issue 11, item 5): at α = 10 the penalty layer's stiffness per area, p/h with h a quarter
// of the surface tetrahedron's height, is 40 E/H, about 40× its element's own, so the contact
// alone set the step 1.1–4.3× below the element limit on the study's meshes (reports/fem/
// mesh_step.md; a global Lanczos estimate of the same all-faces system agrees within 10 %, so
// the bound is not what is loose). The step then follows the penalty, not the element size.
// Lowering p to the factor costs penetration compliance: E/p of the elements' own shortening
// (Munjiza 2004, eqs 2.56–2.57), measured in reports/fem/mesh_step.md on the FEM/DEM gates.
//
// How: ω² of elements plus face springs grows with s (the springs are linear in p), the element
// part does not; regula falsi (Illinois) on ω(s)/ω_element − factor (undamped, so a body's
// damping_ratio leaves its penalty alone) from s = 0 (ratio 1) and s = 1 keeps the last s that
// meets the factor, at most six evaluations of the bound, stopping once the factor met is within
// 2 % of the one asked (so in [0.98, 1] × factor unless the six run out first: 4 of the 161
// lowered meshes of the bench_fem set stopped at 0.962–0.980, reports/fem/collision_cost.md).
// Rigid bodies have no element limit and are left alone.
double limit_penalty(World& world, double factor);

// The same bound met locally (ContactStepFix::face_penalty): the penalty is lowered only on the
// surface faces whose nodes set the step, each node i by s_i = min(1, γ ω_e² m_i / c_i) (c_i =
// Σ k_f/3 over its faces, the Gershgorin row of its face springs; ω_e the body's element bound),
// a face by the least s of its nodes and a contact tetrahedron by the least s of its surface nodes
// (World::tet_penalty_scale; a pair takes the smaller of its two). γ = factor² − 1 meets the
// factor by Weyl's sum alone (ω² ≤ ω_e² + max_i s_i c_i / m_i ≤ factor² ω_e²); regula falsi on
// the combined bound then raises γ towards the factor, at most six evaluations, stopping within
// 2 % of it as limit_penalty does. The penalty of a face is so scaled with the stiffness and mass
// of the element under it: large elements keep α as asked, the small or thin ones that set the
// step get less. Returns the least face scale.
double limit_face_penalty(World& world, double factor);

// The same bound met by contact (nodal) mass scaling (ContactStepFix::mass): each surface node
// i whose face springs set the step gets the lumped mass c_i / (γ ω_e²) instead of m_i where that
// is more (World::added_mass, also in World::mass), γ found as in limit_face_penalty; the penalty
// stays as asked. Forces are unchanged, so linear momentum Σ m v (with the added mass) is
// conserved exactly as before, but the body starts with (m + Δm) v and ½ (m + Δm) v²: the impact
// is that of a heavier body by Δm/m (a Hertz peak ∝ m^{3/5}, duration ∝ m^{2/5}), with the added
// mass on the surface where it also slows the local response. Returns the largest Δm/m over
// the bodies (0: nothing added).
double scale_contact_mass(World& world, double factor);

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
