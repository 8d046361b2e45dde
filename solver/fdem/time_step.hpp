// Predicted critical time step of an FEM/DEM world: element limit and penalty-contact limit.
#pragma once

#include <string>

#include "fdem/fdem_world.hpp"

namespace asperity::fdem {

struct CriticalStep {
  double element = 0;   // s, 2/ω_e (damped) of the stiffest element (fem::element_critical_step)
  double contact = 0;   // s, 2/ω_c of the stiffest penalty contact
  double critical = 0;  // s, 2/√(ω_e² + ω_c²), with the damping correction of the element part
  std::string limited_by;    // "element" or "contact"
  std::string element_body;  // the body of the stiffest element
};

// Element part: the largest element eigenvalue over the deformable bodies (Irons' bound, exact
// per element, see fem/tet_elements.hpp). Rigid bodies have no element modes.
//
// Contact part: every surface face of a moving body, pressed into another body, adds a stiffness
// k_f = p A (1/h + 1/h') (fdem_world.cpp) distributed over its three nodes by the consistent
// face matrix k_f/12 [[2,1,1],[1,2,1],[1,1,2]], whose rows sum to k_f/3. Gershgorin's theorem on
// M⁻¹K_c then bounds ω_c² by max over nodes of Σ_faces (k_f/3) / m_node, with every surface face
// assumed in contact at once (conservative). A rigid body takes the same node springs through
// its 6 DOF: ω_c² = the largest root of det(K_r − ω² M_r) (time_step.cpp), the contact stiffness
// over its mass and inertia; its nodes' lumped masses would bound it too (the rigid constraint
// only lowers the highest frequency) but about 10× too conservatively.
//
// The two stiffnesses act together, so taking min(dt_element, dt_contact) is not safe when they
// are close; Weyl's inequality λ_max(A + B) ≤ λ_max(A) + λ_max(B) gives ω² ≤ ω_e² + ω_c².
// Finite-strain stiffening of the neo-Hookean law in compression is left to the safety factor.
// The penalty p = αE makes ω_c about √α times ω_e, so the step shrinks by about √α.
CriticalStep critical_step(const World& world);

}  // namespace asperity::fdem
