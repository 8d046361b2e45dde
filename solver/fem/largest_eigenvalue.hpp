// The largest eigenvalue of a small symmetric matrix (the 12×12 element matrices of the critical
// step, fem/tet_elements.cpp), without the others.
//
// Householder reduction to a tridiagonal T (Eigen::Tridiagonalization, the first half of the
// SelfAdjointEigenSolver), then bisection on T's Sturm sequence (Golub & Van Loan 2013, §8.4.1;
// LAPACK dstebz): the number of negative pivots of the LDLᵀ factors of T − x I,
//   q_0 = d_0 − x,  q_i = d_i − x − e_{i−1}² / q_{i−1},
// is the number of eigenvalues below x. The largest lies in [max_i d_i, max_i (d_i + |e_{i−1}| +
// |e_i|)] (a Rayleigh quotient; Gershgorin), and halving that interval until its ends are
// neighbouring doubles gives it to the accuracy of the QR iterations the full solver would run
// after the same reduction (both backward stable: |error| ≤ a small multiple of ε ‖T‖, and for
// these positive semi-definite matrices λ_max = ‖T‖). A QR sweep finds all twelve eigenvalues to
// return one: the bisection took the 12×12 solves of a refined FEM/DEM level's set-up from about
// 22 to about 7 µs each (docs/performance.md, "A refined FEM/DEM level").
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

namespace asperity::fem {

template <int N>
double largest_eigenvalue(const Eigen::Matrix<double, N, N>& a) {
  static_assert(N >= 2, "a 1×1 matrix is its own eigenvalue");
  const Eigen::Tridiagonalization<Eigen::Matrix<double, N, N>> t(a);
  const Eigen::Matrix<double, N, 1> d = t.diagonal();
  const Eigen::Matrix<double, N - 1, 1> e = t.subDiagonal();
  double e2[N - 1];
  double lo = d[0], hi = -std::numeric_limits<double>::infinity(), scale = 0;
  for (int i = 0; i < N; ++i) {
    const double left = i > 0 ? std::abs(e[i - 1]) : 0.0, right = i < N - 1 ? std::abs(e[i]) : 0.0;
    lo = std::max(lo, d[i]);
    hi = std::max(hi, d[i] + left + right);
    scale = std::max(scale, std::abs(d[i]) + left + right);
    if (i < N - 1) e2[i] = e[i] * e[i];
  }
  // A zero pivot is taken as a tiny negative one (dstebz's pivmin), so that the count stays
  // defined; it moves x by far less than the interval's last halving.
  const double pivmin = std::numeric_limits<double>::min() * std::max(1.0, scale * scale);
  // Number of eigenvalues of T below x.
  const auto below = [&](double x) {
    int count = 0;
    double q = d[0] - x;
    for (int i = 0;; ++i) {
      if (std::abs(q) < pivmin) q = -pivmin;
      count += q < 0;
      if (i == N - 1) return count;
      q = d[i + 1] - x - e2[i] / q;
    }
  };
  while (true) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;  // lo and hi are neighbouring doubles
    (below(mid) == N ? hi : lo) = mid;
  }
  return hi;
}

}  // namespace asperity::fem
