// Geometrically linear (small-strain) isotropic elastic 4-node tetrahedron: the pure per-element
// kernel beside the neo-Hookean one (fem/neo_hookean_tet.hpp), for validation against
// linear-elastic solutions (Hertz, the axisymmetric finite sphere of validation/reference).
//
// Why a second law: Hertz's theory and the finite-sphere reference are linear elasticity; the
// neo-Hookean material agrees with them only to first order in the strain, and Hertz contacts here
// strain to p0/E ≈ 7 %. Running the same mesh with the linear law separates the material's own
// (finite-strain) effect from the discretization error (reports/fem/hertz_convergence.md).
//
// Not frame-indifferent: ε = sym(F − I) of a rigid rotation by θ is (cos θ − 1)(I − n nᵀ) ≠ 0, so
// a rotated body carries a spurious stress of order E θ²/2. It is for bodies that stay close to
// their reference orientation; the element loop measures each element's rotation (the axial
// vector of skew(F − I): sin θ for a pure rotation) and the world stops (exit 3) past
// kLinearMaxRotation (fem/tet_elements.hpp).
//
// Energy density (Zienkiewicz & Taylor, vol. 1, ch. 6): Ψ = ½ ε:C:ε = λ/2 (tr ε)² + μ ε:ε, with
//   ε = sym(F − I),   σ = P = λ tr ε I + 2 μ ε   (first and second Piola and Cauchy coincide),
// and the nodal forces −V₀ P ∇N_a as the neo-Hookean kernel's. Its stiffness is tet_stiffness
// (fem/neo_hookean_tet.hpp) exactly, at every state: the critical step is the same.
#pragma once

#include <cmath>

#include "solver/fem/neo_hookean_tet.hpp"

namespace asperity::fem {

// H = −V₀ P Bᵀ with P = λ tr ε I + 2 μ ε, ε = sym(F − I), from F as tet_deformation stores it,
// into h as tet_nodal_forces stores it; returns the element's rotation |axial(skew F)| (sin θ for
// a rigid rotation by θ).
template <int S>
inline double linear_tet_nodal_forces(const double* b, double volume, Lame lame, const double* F,
                                      double* h) {
  const double e00 = F[0] - 1, e11 = F[4 * S] - 1, e22 = F[8 * S] - 1;
  const double e01 = 0.5 * (F[S] + F[3 * S]), e02 = 0.5 * (F[2 * S] + F[6 * S]),
               e12 = 0.5 * (F[5 * S] + F[7 * S]);
  const double mu2 = 2 * lame.mu;
  const double l = lame.lambda * (e00 + e11 + e22);
  const double P00 = l + mu2 * e00, P11 = l + mu2 * e11, P22 = l + mu2 * e22;
  const double P01 = mu2 * e01, P02 = mu2 * e02, P12 = mu2 * e12;
  tet_piola_forces<S>(b, volume, P00, P01, P02, P01, P11, P12, P02, P12, P22, h);
  const double w0 = 0.5 * (F[7 * S] - F[5 * S]), w1 = 0.5 * (F[2 * S] - F[6 * S]),
               w2 = 0.5 * (F[3 * S] - F[S]);
  return std::sqrt(w0 * w0 + w1 * w1 + w2 * w2);
}

// V₀ Ψ = V₀ (λ/2 (tr ε)² + μ ε:ε), J, from F as tet_deformation stores it.
template <int S>
inline double linear_tet_strain_energy(double volume, Lame lame, const double* F) {
  const double e00 = F[0] - 1, e11 = F[4 * S] - 1, e22 = F[8 * S] - 1;
  const double e01 = 0.5 * (F[S] + F[3 * S]), e02 = 0.5 * (F[2 * S] + F[6 * S]),
               e12 = 0.5 * (F[5 * S] + F[7 * S]);
  const double tr = e00 + e11 + e22;
  const double ee = e00 * e00 + e11 * e11 + e22 * e22 + 2 * (e01 * e01 + e02 * e02 + e12 * e12);
  return volume * (0.5 * lame.lambda * tr * tr + lame.mu * ee);
}

// Nodal internal forces of one element (added to f0..f3, N) from its current node positions;
// returns J, and the element's rotation in `rotation` (see linear_tet_nodal_forces). The energy
// is defined for any F, but an element with J ≤ 0 has passed through zero volume: as for
// neo_hookean_tet_forces, nothing is added and the caller reports it. `energy` (J) gets V₀ Ψ when
// kEnergy.
template <bool kEnergy>
inline double linear_elastic_tet_forces(const double* dm_inv, double volume, Lame lame,
                                        const double* x0, const double* x1, const double* x2,
                                        const double* x3, double* f0, double* f1, double* f2,
                                        double* f3, double* energy, double* rotation) {
  const double d[9] = {x1[0] - x0[0], x2[0] - x0[0], x3[0] - x0[0], x1[1] - x0[1], x2[1] - x0[1],
                       x3[1] - x0[1], x1[2] - x0[2], x2[2] - x0[2], x3[2] - x0[2]};
  double F[9], C[9], h[9];
  const double J = tet_deformation<1>(d, dm_inv, F, C);
  if (!(J > 0)) return J;
  *rotation = linear_tet_nodal_forces<1>(dm_inv, volume, lame, F, h);
  tet_scatter<1>(h, f0, f1, f2, f3);
  if constexpr (kEnergy) *energy += linear_tet_strain_energy<1>(volume, lame, F);
  return J;
}

}  // namespace asperity::fem
