// A deformable body's elements as plain arrays, the element loop (internal forces, strain
// energy, optional viscous damping), lumped masses and the element critical time step.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "fem/neo_hookean_tet.hpp"

namespace asperity::fem {

// Elements of one body (one material). Node indices are global (into the world's node arrays).
struct TetElements {
  Eigen::Matrix4Xi tets;       // node indices, positive reference volume
  std::vector<double> dm_inv;  // 9 per element, Dm⁻¹ column-major
  std::vector<double> volume;  // m³, V₀
  Lame lame;
  double density = 0;  // kg/m³
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
};

// f += internal (elastic, and viscous when damping > 0 using velocities v) nodal forces.
InternalForceResult add_internal_forces(const TetElements& e, const Eigen::Matrix3Xd& x,
                                        const Eigen::Matrix3Xd& v, Eigen::Matrix3Xd& f,
                                        bool with_energy);

// Element critical step: central differences are stable for ω dt ≤ 2 (with modal damping ratio ξ:
// dt ≤ (2/ω)(√(1+ξ²) − ξ), Belytschko, Liu & Moran 2000, eq. 6.2.23), and the largest global ω
// is bounded by the largest element ω (Irons' element-eigenvalue theorem, Hughes 2000, §9.3.2),
// ω_e² = λ_max(K_e) / (ρ V₀ / 4) with K_e the element stiffness. λ_max comes from an exact 12×12
// symmetric eigen-solve, not from L/c, which is not conservative for distorted elements.
struct ElementStep {
  double omega_max = 0;  // rad/s, largest element ω
  double dt = 0;         // s, the damped bound at omega_max
  int element = -1;      // which element
};
ElementStep element_critical_step(const TetElements& e);

}  // namespace asperity::fem
