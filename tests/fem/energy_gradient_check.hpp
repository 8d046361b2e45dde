// The check both element laws' tests make (test_neo_hookean_tet.cpp, test_linear_elastic_tet.cpp):
// the nodal forces of one tetrahedron are minus the gradient of its energy V₀Ψ, by central
// differences at a finite strain of the unit reference tetrahedron.
#pragma once

#include <gtest/gtest.h>

namespace asperity::fem::test_material {

// `kernel(x, f)` fills the forces f of nodes x (4 × 3, m) and returns the element's energy (J).
// `tolerance` (N) is the caller's: its reason depends on the law's energy.
template <class Kernel>
void expect_forces_are_minus_energy_gradient(Kernel kernel, double tolerance) {
  double x[4][3] = {{0.05, -0.02, 0.01}, {1.1, 0.03, -0.05}, {0.02, 0.85, 0.1}, {-0.1, 0.05, 1.2}};
  double f[4][3] = {}, scratch[4][3] = {};
  kernel(x, f);
  const double h = 1e-6;  // m
  for (int a = 0; a < 4; ++a) {
    for (int r = 0; r < 3; ++r) {
      const double keep = x[a][r];
      x[a][r] = keep + h;
      const double wp = kernel(x, scratch);
      x[a][r] = keep - h;
      const double wm = kernel(x, scratch);
      x[a][r] = keep;
      EXPECT_NEAR(f[a][r], -(wp - wm) / (2 * h), tolerance) << a << "," << r;
    }
  }
}

}  // namespace asperity::fem::test_material
