// The contact step's remedies: where the penalty contact would pull a deformable body's predicted
// step (time_step.hpp) more than a factor below its elements' own, the penalty is lowered (for
// every face or face by face) or mass is added to the surface nodes that set it
// (fdem::ContactStepFix; issue 11, item 5).
#pragma once

#include "solver/fdem/fdem_world.hpp"

namespace asperity::fdem {

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

// scale_contact_mass with the factor lowered below `factor` as far as the mass added stays
// within `max_added` of every deformable body's mass (where the factor asked already adds more,
// the factor asked: it is the most the contact may pull the step down, the budget only lets it
// pull less). Returns the factor met (the least over the bodies; the budget is the body's).
//
// Why: the reference levels of the particle-geometry study (study/source_reference.hpp) at the
// study's factor 2 met by mass ran at the contact's step, 2.6 times below their elements' own
// (summary dt_contact against dt_element, every level of reports/study-wide-source), while the
// mass added at their finest level was about 1e-5 of the body's. A Hertz peak moves by 3/5 of
// Δm/m and the impulse by about Δm/m, so a budget of 1e-4 moves neither by more than 0.01 %; on
// ballast_01-o1's finest level it lets the factor fall to 1.17: 1.7 times fewer steps
// (docs/physics.md, "Time step").
//
// How: for the factor asked, γ as scale_contact_mass finds it; then the least γ whose added mass
// (Σ max(0, c_i/(γ ω_e²) − m_i), which grows as γ falls) is within the budget, by bisection in
// log γ on the nodes alone, and one step bound at that γ for the factor it meets; where that is
// below kLeastContactFactor (the mass would then lengthen the elements' own step: the budget
// alone gave 0.73 and 0.81 on two finest levels at h/8), the least γ that meets it instead.
double scale_contact_mass_within(World& world, double factor, double max_added);

// The least factor scale_contact_mass_within meets: at 1 the contact's springs would cost no step
// at all, and below it the mass added would also lengthen the elements' own step.
inline constexpr double kLeastContactFactor = 1.05;

}  // namespace asperity::fdem
