// The element loop of the deformable bodies (add_internal_forces, fem/tet_elements.hpp): internal
// forces, strain energy and viscous forces, element batch by element batch, in target clones.
//
// This file is compiled with -ffp-contract=fast stated (solver/fem/CMakeLists.txt; GCC's C++
// default already, -std=c++20 included: only ISO C modes turn it off), so the clones for targets
// with FMA fuse multiply-adds. Contraction changes each element's forces by round-off only (a fused
// a·b + c rounds once where a·b then + c round twice);
// TetElements.BatchedLoopEqualsTheOneElementKernel holds the loop to the one-element kernel at that
// level.
#include <algorithm>
#include <cmath>

#include "solver/fem/tet_elements.hpp"

namespace asperity::fem {
namespace {

// Kelvin–Voigt viscous forces of one element (see TetElements::damping); returns their power.
double add_viscous_forces(const double* b, double volume, Lame lame, double beta,
                          const double* x[4], const double* v[4], double* f[4]) {
  Mat3 ds, dv;
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) {
      ds(r, c) = x[c + 1][r] - x[0][r];
      dv(r, c) = v[c + 1][r] - v[0][r];
    }
  }
  const Eigen::Map<const Mat3> bm(b);
  const Mat3 F = ds * bm, Fdot = dv * bm;
  const Mat3 Finv = F.inverse();
  const Mat3 L = Fdot * Finv;
  const Mat3 D = 0.5 * (L + L.transpose());
  const Mat3 sigma = beta * (lame.lambda * D.trace() * Mat3::Identity() + 2 * lame.mu * D);
  const double J = F.determinant();
  // P_v = J σ_v F⁻ᵀ; forces −V₀ P_v ∇N_a.
  const Mat3 H = -volume * J * sigma * Finv.transpose() * bm.transpose();
  double power = 0;
  for (int a = 0; a < 3; ++a) {
    for (int r = 0; r < 3; ++r) {
      f[a + 1][r] += H(r, a);
      f[0][r] -= H(r, a);
      power += H(r, a) * (v[a + 1][r] - v[0][r]);
    }
  }
  return power;
}

// Elements per batch of the element loop: its structure-of-arrays scratch (about 40 doubles per
// element) stays in L1.
constexpr int kBatch = 32;

// The element loop, batch by batch, for one law (chosen once per body): gather the batch's edges
// and Dm⁻¹ into structure of arrays, run the kernel's stages (fem/neo_hookean_tet.hpp, or
// fem/linear_elastic_tet.hpp, which has no logarithm) over it as plain loops the compiler
// vectorizes, the logarithms in between (fem/log_series.hpp, vectorized too), then add the
// forces to the nodes in element order. Each element's expressions and the order of the
// additions into f and the energy are those of neo_hookean_tet_forces called element by element;
// only the schedule differs, and where the target has FMA the contractions: the same result to
// round-off (tests/fem/test_neo_hookean_tet.cpp; to the bit in the baseline copy, which has no
// FMA). Always inlined: a function the target clones below call is compiled once, for the
// baseline, so only a copy inside each clone is built for its target.
template <bool kEnergy, ElasticLaw kLaw>
[[gnu::always_inline]] inline InternalForceResult loop(const TetElements& e,
                                                       const Eigen::Matrix3Xd& x,
                                                       const Eigen::Matrix3Xd& v,
                                                       Eigen::Matrix3Xd& f) {
  InternalForceResult out;
  const int* t = e.tets.data();
  const double* xs = x.data();
  double* fs = f.data();
  const int n = e.size();
  double energy = 0;
  alignas(64) double d[9 * kBatch], b[9 * kBatch], F[9 * kBatch], C[9 * kBatch], h[9 * kBatch];
  alignas(64) double J[kBatch], ln_j[kBatch], w[kBatch], rotation[kBatch];
  for (int k0 = 0; k0 < n; k0 += kBatch) {
    const int m = std::min(kBatch, n - k0);
    for (int i = 0; i < m; ++i) {
      const int* tk = t + 4 * (k0 + i);
      const double *x0 = xs + 3 * tk[0], *x1 = xs + 3 * tk[1], *x2 = xs + 3 * tk[2],
                   *x3 = xs + 3 * tk[3];
      for (int r = 0; r < 3; ++r) {
        d[(3 * r) * kBatch + i] = x1[r] - x0[r];
        d[(3 * r + 1) * kBatch + i] = x2[r] - x0[r];
        d[(3 * r + 2) * kBatch + i] = x3[r] - x0[r];
      }
      const double* bk = &e.dm_inv[9 * static_cast<std::size_t>(k0 + i)];
      for (int c = 0; c < 9; ++c) b[c * kBatch + i] = bk[c];
    }
    for (int i = 0; i < m; ++i) J[i] = tet_deformation<kBatch>(d + i, b + i, F + i, C + i);
    const double* vol = &e.volume[static_cast<std::size_t>(k0)];
    if constexpr (kLaw == ElasticLaw::neo_hookean) {
      // ln J of the whole batch as plain arithmetic the compiler vectorizes (fem/log_series.hpp),
      // then the rare J it does not cover: an inverted element (J ≤ 0) gets ln J = 0 (and J = 1)
      // for the arithmetic and adds nothing below; a subnormal or infinite J takes std::log, as
      // tet_log_j does for one element.
      for (int i = 0; i < m; ++i) ln_j[i] = log_series(J[i]);
      for (int i = 0; i < m; ++i) {
        if (!log_series_covers(J[i])) ln_j[i] = J[i] > 0 ? std::log(J[i]) : 0.0;
      }
      for (int i = 0; i < m; ++i) {
        tet_nodal_forces<kBatch>(b + i, vol[i], e.lame, J[i] > 0 ? J[i] : 1.0, ln_j[i], F + i,
                                 C + i, h + i);
        if constexpr (kEnergy) w[i] = tet_strain_energy<kBatch>(vol[i], e.lame, ln_j[i], F + i);
      }
    } else {
      for (int i = 0; i < m; ++i) {
        rotation[i] = linear_tet_nodal_forces<kBatch>(b + i, vol[i], e.lame, F + i, h + i);
        if constexpr (kEnergy) w[i] = linear_tet_strain_energy<kBatch>(vol[i], e.lame, F + i);
      }
    }
    for (int i = 0; i < m; ++i) {
      if (!(J[i] > 0)) {
        if (out.inverted < 0) out.inverted = k0 + i, out.inverted_j = J[i];
        continue;
      }
      if constexpr (kLaw == ElasticLaw::linear) {
        if (rotation[i] > out.max_rotation) out.max_rotation = rotation[i], out.rotated = k0 + i;
      }
      const int* tk = t + 4 * (k0 + i);
      tet_scatter<kBatch>(h + i, fs + 3 * tk[0], fs + 3 * tk[1], fs + 3 * tk[2], fs + 3 * tk[3]);
      if constexpr (kEnergy) energy += w[i];
    }
  }
  out.energy = energy;
  if (e.damping > 0 && out.inverted < 0) {
    const double* vs = v.data();
    for (int k = 0; k < n; ++k) {
      const double* xp[4];
      const double* vp[4];
      double* fp[4];
      for (int a = 0; a < 4; ++a) {
        const int i = 3 * t[4 * k + a];
        xp[a] = xs + i;
        vp[a] = vs + i;
        fp[a] = fs + i;
      }
      out.damping_power += add_viscous_forces(&e.dm_inv[9 * static_cast<std::size_t>(k)],
                                              e.volume[k], e.lame, e.damping, xp, vp, fp);
    }
  }
  return out;
}

}  // namespace

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
// Copies for x86-64-v4 (AVX-512) and x86-64-v3 (AVX2 with FMA) beside the baseline one (SSE2),
// chosen at load time: the batched stages run 8 or 4 elements per instruction instead of 2,
// their multiply-adds fused. The two FMA copies fuse the same operations, so they give the same
// bits; the baseline differs from them by round-off.
[[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]]
#endif
InternalForceResult
add_internal_forces(const TetElements& e, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                    Eigen::Matrix3Xd& f, bool with_energy) {
  if (e.law == ElasticLaw::linear) {
    return with_energy ? loop<true, ElasticLaw::linear>(e, x, v, f)
                       : loop<false, ElasticLaw::linear>(e, x, v, f);
  }
  return with_energy ? loop<true, ElasticLaw::neo_hookean>(e, x, v, f)
                     : loop<false, ElasticLaw::neo_hookean>(e, x, v, f);
}

}  // namespace asperity::fem
