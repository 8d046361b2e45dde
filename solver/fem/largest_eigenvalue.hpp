// The largest eigenvalue of a small symmetric matrix (the 12×12 element matrices of the critical
// step, fem/tet_elements.cpp), without the others.
//
// Householder reduction to a tridiagonal T (Eigen::Tridiagonalization, the first half of the
// SelfAdjointEigenSolver), then Newton's method on T's characteristic polynomial from above,
// evaluated through the pivots of the LDLᵀ factors of T − x I (the Sturm sequence, Golub & Van
// Loan 2013, §8.4.1),
//   q_0 = d_0 − x,  q_i = d_i − x − e_{i−1}² / q_{i−1},  det(T − x I) = Π q_i.
// The largest eigenvalue lies in [max_i d_i, max_i (d_i + |e_{i−1}| + |e_i|)] (a Rayleigh
// quotient; Gershgorin). The result equals the QR iterations' that the full solver runs after the
// same reduction to round-off (tests/fem/test_element_step.cpp): a QR sweep finds all twelve
// eigenvalues to return one (docs/performance.md, "A refined FEM/DEM level").
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
  double lo = d[0], hi = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < N; ++i) {
    const double left = i > 0 ? std::abs(e[i - 1]) : 0.0, right = i < N - 1 ? std::abs(e[i]) : 0.0;
    lo = std::max(lo, d[i]);
    hi = std::max(hi, d[i] + left + right);
    if (i < N - 1) e2[i] = e[i] * e[i];
  }
  // Newton on det(T − x I) = Π q_i from the Gershgorin bound down: above the largest eigenvalue
  // every pivot is negative and d ln|det|/dx = Σ_j 1/(x − λ_j) = Σ_i q_i'/q_i, so each step
  // 1/Σ_j 1/(x − λ_j) ≤ x − λ_max never passes it, and the iterates descend onto it
  // (quadratically onto a simple one, halving the distance onto a double one). It stops where
  // round-off ends the descent or turns a pivot's sign.
  double x = hi;
  for (int it = 0; it < 200; ++it) {
    double q = d[0] - x, dq = -1, sum = 0;
    bool above = q < 0;
    for (int i = 0; above; ++i) {
      sum += dq / q;
      if (i == N - 1) break;
      const double next = d[i + 1] - x - e2[i] / q;
      dq = -1 + e2[i] * dq / (q * q);
      q = next;
      above = q < 0;
    }
    if (!above || !(sum > 0)) break;  // on the largest eigenvalue to round-off
    const double next = x - 1 / sum;
    if (!(next < x) || next < lo) break;
    x = next;
  }
  return x;
}

}  // namespace asperity::fem
