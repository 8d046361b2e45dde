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

#include <cfloat>
#include <cmath>

#include <Eigen/Core>

#include "solver/core/vec.hpp"
#include "solver/fem/log_series.hpp"

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

// The kernel in two stages around the logarithm, shared by the one-element form below and the
// batched element loop (fem/internal_forces.cpp), which runs each stage over a batch of elements
// in structure of arrays so that the compiler vectorizes it; the same expressions in the same
// order give the same bits either way, except where a target with FMA fuses multiply-adds (the
// loop's clones for such targets do: round-off). Component c of an element's 9 values sits at [c ·
// S]: S = 1 for one element, the batch size for a batch.
//
// Stage 1: F = Ds B and cof F (= J F⁻ᵀ), row-major (F[(3r + c) S] = F(r, c)), from Ds
// (d[(3r + c) S] = row r of edge c, x_{c+1} − x₀) and B = Dm⁻¹ (column-major, b[(r + 3c) S]);
// returns J = det F.
template <int S>
inline double tet_deformation(const double* d, const double* b, double* F, double* C) {
  const double d00 = d[0], d01 = d[S], d02 = d[2 * S];
  const double d10 = d[3 * S], d11 = d[4 * S], d12 = d[5 * S];
  const double d20 = d[6 * S], d21 = d[7 * S], d22 = d[8 * S];
  const double b0 = b[0], b1 = b[S], b2 = b[2 * S], b3 = b[3 * S], b4 = b[4 * S], b5 = b[5 * S],
               b6 = b[6 * S], b7 = b[7 * S], b8 = b[8 * S];
  const double F00 = d00 * b0 + d01 * b1 + d02 * b2;
  const double F01 = d00 * b3 + d01 * b4 + d02 * b5;
  const double F02 = d00 * b6 + d01 * b7 + d02 * b8;
  const double F10 = d10 * b0 + d11 * b1 + d12 * b2;
  const double F11 = d10 * b3 + d11 * b4 + d12 * b5;
  const double F12 = d10 * b6 + d11 * b7 + d12 * b8;
  const double F20 = d20 * b0 + d21 * b1 + d22 * b2;
  const double F21 = d20 * b3 + d21 * b4 + d22 * b5;
  const double F22 = d20 * b6 + d21 * b7 + d22 * b8;
  const double C00 = F11 * F22 - F12 * F21, C01 = F12 * F20 - F10 * F22,
               C02 = F10 * F21 - F11 * F20;
  F[0] = F00, F[S] = F01, F[2 * S] = F02, F[3 * S] = F10, F[4 * S] = F11, F[5 * S] = F12;
  F[6 * S] = F20, F[7 * S] = F21, F[8 * S] = F22;
  C[0] = C00, C[S] = C01, C[2 * S] = C02;
  C[3 * S] = F02 * F21 - F01 * F22, C[4 * S] = F00 * F22 - F02 * F20,
        C[5 * S] = F01 * F20 - F00 * F21;
  C[6 * S] = F01 * F12 - F02 * F11, C[7 * S] = F02 * F10 - F00 * F12,
        C[8 * S] = F00 * F11 - F01 * F10;
  return F00 * C00 + F01 * C01 + F02 * C02;
}

// H = −V₀ P Bᵀ, column a (the force on node a + 1) = −V₀ Σ_c P(:, c) B(a, c), into
// h[(3r + a) S] = H(r, a) (node 0 takes minus the row sums), for a first Piola–Kirchhoff stress
// P given by its nine components: every element law's last stage (a symmetric P passes its
// upper triangle twice).
template <int S>
inline void tet_piola_forces(const double* b, double volume, double P00, double P01, double P02,
                             double P10, double P11, double P12, double P20, double P21, double P22,
                             double* h) {
  const double b0 = b[0], b1 = b[S], b2 = b[2 * S], b3 = b[3 * S], b4 = b[4 * S], b5 = b[5 * S],
               b6 = b[6 * S], b7 = b[7 * S], b8 = b[8 * S];
  const double v = -volume;
  h[0] = v * (P00 * b0 + P01 * b3 + P02 * b6);
  h[3 * S] = v * (P10 * b0 + P11 * b3 + P12 * b6);
  h[6 * S] = v * (P20 * b0 + P21 * b3 + P22 * b6);
  h[S] = v * (P00 * b1 + P01 * b4 + P02 * b7);
  h[4 * S] = v * (P10 * b1 + P11 * b4 + P12 * b7);
  h[7 * S] = v * (P20 * b1 + P21 * b4 + P22 * b7);
  h[2 * S] = v * (P00 * b2 + P01 * b5 + P02 * b8);
  h[5 * S] = v * (P10 * b2 + P11 * b5 + P12 * b8);
  h[8 * S] = v * (P20 * b2 + P21 * b5 + P22 * b8);
}

// Stage 2, for J > 0 and ln_j = ln J: H = −V₀ P Bᵀ with P = μ F + s cof F, s = (λ ln J − μ)/J,
// into h as tet_piola_forces stores it.
template <int S>
inline void tet_nodal_forces(const double* b, double volume, Lame lame, double J, double ln_j,
                             const double* F, const double* C, double* h) {
  const double mu = lame.mu;
  const double s = (lame.lambda * ln_j - mu) / J;
  tet_piola_forces<S>(
      b, volume, mu * F[0] + s * C[0], mu * F[S] + s * C[S], mu * F[2 * S] + s * C[2 * S],
      mu * F[3 * S] + s * C[3 * S], mu * F[4 * S] + s * C[4 * S], mu * F[5 * S] + s * C[5 * S],
      mu * F[6 * S] + s * C[6 * S], mu * F[7 * S] + s * C[7 * S], mu * F[8 * S] + s * C[8 * S], h);
}

// ln J as every element kernel takes it: log_series (fem/log_series.hpp, which the batched loop
// runs in vector registers) for normal finite J, std::log for subnormal or infinite J (J ≤ 0 is
// an inverted element: the callers skip it). One function for both loops keeps them equal to the
// bit.
inline bool log_series_covers(double J) {
  return J >= DBL_MIN && J <= DBL_MAX;
}
inline double tet_log_j(double J) {
  return log_series_covers(J) ? log_series(J) : std::log(J);
}

// V₀ Ψ, J, of an element with deformation gradient F (as stage 1 stores it) and ln J.
template <int S>
inline double tet_strain_energy(double volume, Lame lame, double ln_j, const double* F) {
  const double trC = F[0] * F[0] + F[S] * F[S] + F[2 * S] * F[2 * S] + F[3 * S] * F[3 * S] +
                     F[4 * S] * F[4 * S] + F[5 * S] * F[5 * S] + F[6 * S] * F[6 * S] +
                     F[7 * S] * F[7 * S] + F[8 * S] * F[8 * S];
  return volume * (0.5 * lame.mu * (trC - 3) - lame.mu * ln_j + 0.5 * lame.lambda * ln_j * ln_j);
}

// Adds an element's nodal forces h (as stage 2 stores them) to its four nodes.
template <int S>
inline void tet_scatter(const double* h, double* f0, double* f1, double* f2, double* f3) {
  f1[0] += h[0], f1[1] += h[3 * S], f1[2] += h[6 * S];
  f2[0] += h[S], f2[1] += h[4 * S], f2[2] += h[7 * S];
  f3[0] += h[2 * S], f3[1] += h[5 * S], f3[2] += h[8 * S];
  f0[0] -= h[0] + h[S] + h[2 * S], f0[1] -= h[3 * S] + h[4 * S] + h[5 * S],
      f0[2] -= h[6 * S] + h[7 * S] + h[8 * S];
}

// Nodal internal forces of one element (added to f0..f3, N) from its current node positions;
// returns J. For J ≤ 0 (an inverted element: the energy is undefined) nothing is added and the
// caller reports the element. `energy` (J) gets V₀ Ψ when kEnergy.
template <bool kEnergy>
inline double neo_hookean_tet_forces(const double* dm_inv, double volume, Lame lame,
                                     const double* x0, const double* x1, const double* x2,
                                     const double* x3, double* f0, double* f1, double* f2,
                                     double* f3, double* energy) {
  const double d[9] = {x1[0] - x0[0], x2[0] - x0[0], x3[0] - x0[0], x1[1] - x0[1], x2[1] - x0[1],
                       x3[1] - x0[1], x1[2] - x0[2], x2[2] - x0[2], x3[2] - x0[2]};
  double F[9], C[9], h[9];
  const double J = tet_deformation<1>(d, dm_inv, F, C);
  if (!(J > 0)) return J;
  const double ln_j = tet_log_j(J);
  tet_nodal_forces<1>(dm_inv, volume, lame, J, ln_j, F, C, h);
  tet_scatter<1>(h, f0, f1, f2, f3);
  if constexpr (kEnergy) *energy += tet_strain_energy<1>(volume, lame, ln_j, F);
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
