// A deformable body's elements as plain arrays, the element loop (internal forces, strain
// energy, optional viscous damping), lumped masses and the element critical time step.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "solver/core/material.hpp"
#include "solver/fem/linear_elastic_tet.hpp"
#include "solver/fem/neo_hookean_tet.hpp"

namespace asperity::fem {

// Elements of one body (one material). Node indices are global (into the world's node arrays).
struct TetElements {
  Eigen::Matrix4Xi tets;       // node indices, positive reference volume
  std::vector<double> dm_inv;  // 9 per element, Dm⁻¹ column-major
  std::vector<double> volume;  // m³, V₀
  Lame lame;
  ElasticLaw law = ElasticLaw::neo_hookean;  // chosen once per body: the loop is templated on it
  double density = 0;                        // kg/m³
  // Kelvin–Voigt viscosity as a fraction of the elastic moduli, s (0: off, the default):
  // σ_v = β (λ tr D I + 2 μ D), D = sym(Ḟ F⁻¹), the rate of deformation — objective, so a
  // rigid rotation dissipates nothing. Modal damping ratio ξ = β ω / 2 (stiffness-proportional
  // Rayleigh damping, Hughes 2000, §9.3.3).
  double damping = 0;

  int size() const { return static_cast<int>(volume.size()); }
};

// Builds the reference data from reference node positions `x` (global indexing). Throws
// InputError naming `what` and the element when an element has non-positive volume.
TetElements make_tet_elements(const Eigen::Matrix3Xd& x, const Eigen::Matrix4Xi& tets, double young,
                              double poisson, double density, double damping,
                              const std::string& what);

// Adds ρ V₀ / 4 to each element node's mass (row-sum lumping, exact for the linear tet's
// translational mass).
void add_lumped_mass(const TetElements& e, std::vector<double>& mass);

struct InternalForceResult {
  double energy = 0;         // Σ V₀ Ψ, J (only when asked)
  double damping_power = 0;  // Σ of the viscous forces' power, W (≤ 0)
  int inverted = -1;         // first element with J ≤ 0, or -1
  double inverted_j = 0;     // its J
  // Linear law only (ElasticLaw::linear): the largest element rotation |axial(skew F)| (sin θ of
  // a rigid rotation by θ), and its element (-1 for neo-Hookean elements, which are objective).
  double max_rotation = 0;
  int rotated = -1;
};

// The largest element rotation the linear law may see before a run stops (exit 3). A rigid
// rotation by θ gives the small strain (cos θ − 1) ≈ −θ²/2 across the rotation axis, a spurious
// stress of E θ²/2. The bound sits above the rotations a linear-elastic validation case makes
// (the Hertz sphere at a/R = 0.15: the contact edge's surface turns by about a/R; measured
// in tests/fem/test_linear_elastic_tet.cpp) and below those of a tumbling body.
inline constexpr double kLinearMaxRotation = 0.25;  // rad (sin θ), spurious strain ≤ 3.2 %

// f += internal (elastic, and viscous when damping > 0 using velocities v) nodal forces.
InternalForceResult add_internal_forces(const TetElements& e, const Eigen::Matrix3Xd& x,
                                        const Eigen::Matrix3Xd& v, Eigen::Matrix3Xd& f,
                                        bool with_energy);

// Element critical step: central differences are stable for ω dt ≤ 2 (with modal damping ratio ξ:
// dt ≤ (2/ω)(√(1+ξ²) − ξ), Belytschko, Liu & Moran 2000, eq. 6.2.23). The largest global ω of
// K u = ω² M u (K = Σ_e K_e assembled, M the lumped mass) is bounded element by element with a
// split of the lumped mass: for any M = Σ_e M_e with M_e ≥ 0 diagonal on element e's nodes (and
// M_e > 0 wherever K_e has stiffness),
//   uᵀ K u = Σ_e u_eᵀ K_e u_e ≤ Σ_e λ_e u_eᵀ M_e u_e ≤ (max_e λ_e) uᵀ M u,  λ_e = λ_max(M_e⁻¹K_e),
// so ω_max² ≤ max_e λ_e by the Rayleigh quotient. Irons' element-eigenvalue theorem (Irons
// 1970; Hughes 2000, §9.3.2) is this argument with the equal share ρV₀/4 per element node; the
// proof holds for any split. The equal share gives the stiffest element no more mass than a
// soft neighbour and is 1.2–3.4× loose in ω on graded or distorted meshes. Here node a's mass
// m_a goes to its elements in proportion to their diagonal stiffness there, m_ea = m_a d_ea / Σ_e'
// d_e'a, d_ea = tr K_e[a,a] (an element that is stiff at a holds a's mass, as the global mode
// does), then a few passes move mass toward the elements with the largest λ_e, m_ea ∝ m_ea λ_e^½,
// keeping the split with the smallest max λ_e. Every split is rigorous, so the passes only sharpen
// it. λ_e is exact, not L/c, which is not conservative for distorted elements: the largest root of
// a cubic for an element alone (tet_elements.cpp, split_eigenvalue_isotropic), a 12×12 symmetric
// eigen-solve of M_e^-½ K_e M_e^-½ for an element with extra stiffness.
//
// `extra` adds stiffness to single elements (e.g. a penalty spring on an element's face, which
// then takes its share of the node masses like the element's own stiffness); the same argument
// bounds ω of K + Σ extra, and more tightly than adding a separate bound for the extra part
// (Weyl's sum) because the mass is not counted twice.
struct ElementStep {
  double omega_max = 0;  // rad/s, bound on the largest global ω
  double dt = 0;         // s, the damped bound at omega_max
  int element = -1;      // the element that sets the bound
};
struct ElementExtraStiffness {
  int element = -1;                 // index into TetElements
  Eigen::Matrix<double, 12, 12> k;  // on the element's four nodes, 3 DOF each, symmetric ≥ 0
};
// `added_mass` (kg, indexed by the global node numbers of e.tets; empty: none) is lumped mass
// beyond ρV/4 on some nodes (contact mass scaling, fdem/contact_step.hpp): it joins those nodes'
// mass before the split, so the bound is that of the scaled mass matrix.
ElementStep element_critical_step(const TetElements& e,
                                  const std::vector<ElementExtraStiffness>& extra = {},
                                  const std::vector<double>& added_mass = {});

}  // namespace asperity::fem
