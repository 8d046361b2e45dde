// Stress measures of one tetrahedron, compressible neo-Hookean (fem/neo_hookean_tet.hpp) or
// small-strain linear (fem/linear_elastic_tet.hpp), from its current node positions: what a
// picture of a deformed body is coloured by.
#pragma once

#include <cmath>

#include "solver/core/material.hpp"
#include "solver/core/vec.hpp"
#include "solver/fem/neo_hookean_tet.hpp"

namespace asperity::fem {

struct TetStress {
  double von_mises = 0;       // Pa, of the Cauchy stress
  double energy_density = 0;  // J/m³ of reference volume, Ψ(F)
  double j = 1;               // det F (≤ 0: inverted, both measures left 0)
};

// F = Ds Dm⁻¹ of the tetrahedron (dm_inv column-major, as TetElements stores it): both laws'
// measures start from it.
inline Mat3 tet_deformation_gradient(const double* dm_inv, const Vec3& x0, const Vec3& x1,
                                     const Vec3& x2, const Vec3& x3) {
  Mat3 ds;
  ds << x1 - x0, x2 - x0, x3 - x0;
  return ds * Eigen::Map<const Mat3>(dm_inv);
}

// The neo-Hookean law's: the Cauchy stress of the energy
// Ψ = μ/2 (tr C − 3) − μ ln J + λ/2 (ln J)² is σ = J⁻¹ P Fᵀ = (μ/J)(b − I) + (λ ln J / J) I with
// b = F Fᵀ (Bonet & Wood 2008, eq. 6.29); von Mises √(3/2 s:s), s its deviator.
inline TetStress neo_hookean_tet_stress(const double* dm_inv, Lame lame, const Vec3& x0,
                                        const Vec3& x1, const Vec3& x2, const Vec3& x3) {
  const Mat3 f = tet_deformation_gradient(dm_inv, x0, x1, x2, x3);
  TetStress out;
  out.j = f.determinant();
  if (!(out.j > 0)) return out;
  const double ln_j = std::log(out.j);
  const Mat3 b = f * f.transpose();
  const Mat3 sigma =
      (lame.mu / out.j) * (b - Mat3::Identity()) + (lame.lambda * ln_j / out.j) * Mat3::Identity();
  const Mat3 s = sigma - sigma.trace() / 3 * Mat3::Identity();
  out.von_mises = std::sqrt(1.5 * s.cwiseProduct(s).sum());
  out.energy_density =
      0.5 * lame.mu * (b.trace() - 3) - lame.mu * ln_j + 0.5 * lame.lambda * ln_j * ln_j;
  return out;
}

// The same for the small-strain linear law: σ = λ tr ε I + 2 μ ε, ε = sym(F − I), and
// Ψ = λ/2 (tr ε)² + μ ε:ε.
inline TetStress linear_tet_stress(const double* dm_inv, Lame lame, const Vec3& x0, const Vec3& x1,
                                   const Vec3& x2, const Vec3& x3) {
  const Mat3 f = tet_deformation_gradient(dm_inv, x0, x1, x2, x3);
  TetStress out;
  out.j = f.determinant();
  if (!(out.j > 0)) return out;
  const Mat3 eps = 0.5 * (f + f.transpose()) - Mat3::Identity();
  const Mat3 sigma = lame.lambda * eps.trace() * Mat3::Identity() + 2 * lame.mu * eps;
  const Mat3 s = sigma - sigma.trace() / 3 * Mat3::Identity();
  out.von_mises = std::sqrt(1.5 * s.cwiseProduct(s).sum());
  out.energy_density =
      0.5 * lame.lambda * eps.trace() * eps.trace() + lame.mu * eps.cwiseProduct(eps).sum();
  return out;
}

// The body's own law.
inline TetStress tet_stress(ElasticLaw law, const double* dm_inv, Lame lame, const Vec3& x0,
                            const Vec3& x1, const Vec3& x2, const Vec3& x3) {
  return law == ElasticLaw::linear ? linear_tet_stress(dm_inv, lame, x0, x1, x2, x3)
                                   : neo_hookean_tet_stress(dm_inv, lame, x0, x1, x2, x3);
}

}  // namespace asperity::fem
