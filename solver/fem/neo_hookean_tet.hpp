// Compressible neo-Hookean 4-node tetrahedron: the pure per-element kernel (nodal forces and
// strain energy from current node positions), and the element stiffness used for the time step.
//
// Why neo-Hookean: impacts rotate and strain elements finitely, and St Venant–Kirchhoff softens
// without bound in compression (it can pass through J = 0 at finite stress); neo-Hookean's
// energy grows without bound as J → 0, and its tangent at F = I is exactly linear elasticity with
// the Lamé constants from E and ν, so small-strain checks (patch test, wave speed, Hertz) test it.
//
// Energy density (Bonet & Wood 2008, eq. 6.27):
//   Ψ(F) = μ/2 (tr FᵀF − 3) − μ ln J + λ/2 (ln J)²,            J = det F
// First Piola–Kirchhoff stress (eq. 6.28 mapped back by P = J σ F⁻ᵀ):
//   P = μ F + (λ ln J − μ) F⁻ᵀ = μ F + (λ ln J − μ)/J · cof F
// Linear tetrahedron: F = Ds Dm⁻¹ with Ds = [x1−x0, x2−x0, x3−x0] and Dm the same in the
// reference; the internal force on node a is −V₀ P ∇N_a, i.e. the columns of −V₀ P Dm⁻ᵀ for
// nodes 1..3 and minus their sum for node 0 (Sifakis & Barbič 2012, §4.3).
#pragma once

#include <cmath>

#include <Eigen/Core>

#include "core/vec.hpp"

namespace asperity::fem {

struct Lame {
  double lambda = 0;  // Pa
  double mu = 0;      // Pa
};

// λ = Eν/((1+ν)(1−2ν)), μ = E/(2(1+ν)).
inline Lame lame_from(double young, double poisson) {
  return {.lambda = young * poisson / ((1 + poisson) * (1 - 2 * poisson)),
          .mu = young / (2 * (1 + poisson))};
}

// Reference data of one element. dm_inv is Dm⁻¹ stored column-major (9 doubles): its rows are
// the reference gradients ∇N₁, ∇N₂, ∇N₃ (∇N₀ = −their sum).
struct TetReference {
  Mat3 dm_inv;
  double volume = 0;  // m³, V₀ = det Dm / 6; non-positive means the element is inverted
};

inline TetReference tet_reference(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3) {
  Mat3 dm;
  dm << x1 - x0, x2 - x0, x3 - x0;
  const double det = dm.determinant();
  return {.dm_inv = det > 0 ? Mat3(dm.inverse()) : Mat3::Zero(), .volume = det / 6};
}

// Nodal internal forces of one element (added to f0..f3, N) from its current node positions;
// returns J. For J ≤ 0 (an inverted element: the energy is undefined) nothing is added and the
// caller reports the element. `energy` (J) gets V₀ Ψ when kEnergy.
template <bool kEnergy>
inline double neo_hookean_tet_forces(const double* dm_inv, double volume, Lame lame,
                                     const double* x0, const double* x1, const double* x2,
                                     const double* x3, double* f0, double* f1, double* f2,
                                     double* f3, double* energy) {
  // Ds columns.
  const double d00 = x1[0] - x0[0], d10 = x1[1] - x0[1], d20 = x1[2] - x0[2];
  const double d01 = x2[0] - x0[0], d11 = x2[1] - x0[1], d21 = x2[2] - x0[2];
  const double d02 = x3[0] - x0[0], d12 = x3[1] - x0[1], d22 = x3[2] - x0[2];
  const double* b = dm_inv;  // b[r + 3c] = B(r, c)
  // F = Ds B.
  const double F00 = d00 * b[0] + d01 * b[1] + d02 * b[2];
  const double F01 = d00 * b[3] + d01 * b[4] + d02 * b[5];
  const double F02 = d00 * b[6] + d01 * b[7] + d02 * b[8];
  const double F10 = d10 * b[0] + d11 * b[1] + d12 * b[2];
  const double F11 = d10 * b[3] + d11 * b[4] + d12 * b[5];
  const double F12 = d10 * b[6] + d11 * b[7] + d12 * b[8];
  const double F20 = d20 * b[0] + d21 * b[1] + d22 * b[2];
  const double F21 = d20 * b[3] + d21 * b[4] + d22 * b[5];
  const double F22 = d20 * b[6] + d21 * b[7] + d22 * b[8];
  // cof F (= J F⁻ᵀ).
  const double C00 = F11 * F22 - F12 * F21, C01 = F12 * F20 - F10 * F22,
               C02 = F10 * F21 - F11 * F20;
  const double C10 = F02 * F21 - F01 * F22, C11 = F00 * F22 - F02 * F20,
               C12 = F01 * F20 - F00 * F21;
  const double C20 = F01 * F12 - F02 * F11, C21 = F02 * F10 - F00 * F12,
               C22 = F00 * F11 - F01 * F10;
  const double J = F00 * C00 + F01 * C01 + F02 * C02;
  if (!(J > 0)) return J;
  const double lnJ = std::log(J);
  const double mu = lame.mu;
  const double s = (lame.lambda * lnJ - mu) / J;
  // H = −V₀ P Bᵀ, with P = μ F + s cof F.
  const double P00 = mu * F00 + s * C00, P01 = mu * F01 + s * C01, P02 = mu * F02 + s * C02;
  const double P10 = mu * F10 + s * C10, P11 = mu * F11 + s * C11, P12 = mu * F12 + s * C12;
  const double P20 = mu * F20 + s * C20, P21 = mu * F21 + s * C21, P22 = mu * F22 + s * C22;
  const double v = -volume;
  // Column a of H (node a+1): −V₀ P · (row a of B) = −V₀ Σ_c P(:, c) B(a, c).
  const double h00 = v * (P00 * b[0] + P01 * b[3] + P02 * b[6]);
  const double h10 = v * (P10 * b[0] + P11 * b[3] + P12 * b[6]);
  const double h20 = v * (P20 * b[0] + P21 * b[3] + P22 * b[6]);
  const double h01 = v * (P00 * b[1] + P01 * b[4] + P02 * b[7]);
  const double h11 = v * (P10 * b[1] + P11 * b[4] + P12 * b[7]);
  const double h21 = v * (P20 * b[1] + P21 * b[4] + P22 * b[7]);
  const double h02 = v * (P00 * b[2] + P01 * b[5] + P02 * b[8]);
  const double h12 = v * (P10 * b[2] + P11 * b[5] + P12 * b[8]);
  const double h22 = v * (P20 * b[2] + P21 * b[5] + P22 * b[8]);
  f1[0] += h00, f1[1] += h10, f1[2] += h20;
  f2[0] += h01, f2[1] += h11, f2[2] += h21;
  f3[0] += h02, f3[1] += h12, f3[2] += h22;
  f0[0] -= h00 + h01 + h02, f0[1] -= h10 + h11 + h12, f0[2] -= h20 + h21 + h22;
  if constexpr (kEnergy) {
    const double trC = F00 * F00 + F01 * F01 + F02 * F02 + F10 * F10 + F11 * F11 + F12 * F12 +
                       F20 * F20 + F21 * F21 + F22 * F22;
    *energy += volume * (0.5 * mu * (trC - 3) - mu * lnJ + 0.5 * lame.lambda * lnJ * lnJ);
  }
  return J;
}

// Linear element stiffness at the reference state (the neo-Hookean tangent at F = I):
// K_ab = V₀ [λ ∇N_a ∇N_bᵀ + μ ∇N_b ∇N_aᵀ + μ (∇N_a·∇N_b) I] (Zienkiewicz & Taylor, vol. 1, ch. 6).
inline Eigen::Matrix<double, 12, 12> tet_stiffness(const TetReference& ref, Lame lame) {
  Eigen::Matrix<double, 3, 4> g;
  g.col(1) = ref.dm_inv.row(0).transpose();
  g.col(2) = ref.dm_inv.row(1).transpose();
  g.col(3) = ref.dm_inv.row(2).transpose();
  g.col(0) = -(g.col(1) + g.col(2) + g.col(3));
  Eigen::Matrix<double, 12, 12> k;
  for (int a = 0; a < 4; ++a) {
    for (int b = 0; b < 4; ++b) {
      k.block<3, 3>(3 * a, 3 * b) =
          ref.volume * (lame.lambda * g.col(a) * g.col(b).transpose() +
                        lame.mu * g.col(b) * g.col(a).transpose() +
                        lame.mu * g.col(a).dot(g.col(b)) * Mat3::Identity());
    }
  }
  return k;
}

}  // namespace asperity::fem
