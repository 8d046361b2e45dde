// The state both element laws' batched-loop tests run (test_neo_hookean_tet.cpp,
// test_linear_elastic_tet.cpp): a ball mesh's nodes moved by a deterministic 1 % jiggle, with
// element 100 turned inside out (its fourth node reflected through its first), so the loop must
// both compute and report an inverted element. `separated` gives every element nodes of its own,
// so that the loop's forces on them are that element's alone, to be compared element by element;
// KernelAgreement and expect_batched_equals_kernel are that comparison, once for both laws.
#pragma once

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "solver/fem/tet_elements.hpp"

namespace asperity::fem::test_material {

inline Eigen::Matrix3Xd strained_ball(const TetElements& e, const Eigen::Matrix3Xd& nodes) {
  Eigen::Matrix3Xd x = nodes;
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    const double t = static_cast<double>(i);
    x.col(i) += 0.01 * Vec3(std::sin(3.0 * t), std::cos(5.0 * t), std::sin(7.0 * t));
  }
  x.col(e.tets(3, 100)) = x.col(e.tets(0, 100)) - (x.col(e.tets(3, 100)) - x.col(e.tets(0, 100)));
  return x;
}

// The elements of `e` in the state `x`, each with four nodes of its own (element k's node a is node
// 4k + a): the same reference data and element order.
struct Separated {
  TetElements e;
  Eigen::Matrix3Xd x;
};
inline Separated separated(const TetElements& e, const Eigen::Matrix3Xd& x) {
  Separated s{.e = e, .x = Eigen::Matrix3Xd(3, 4 * e.size())};
  for (int k = 0; k < e.size(); ++k) {
    for (int a = 0; a < 4; ++a) {
      s.e.tets(a, k) = 4 * k + a;
      s.x.col(4 * k + a) = x.col(e.tets(a, k));
    }
  }
  return s;
}

// The force scale of element k under a unit strain, V₀ (λ + 2μ) max_a |∇N_a|, N: the yardstick of
// the round-off between two schedules of the same element arithmetic.
inline double unit_strain_force(const TetElements& e, int k) {
  const Eigen::Map<const Mat3> b(&e.dm_inv[9 * static_cast<std::size_t>(k)]);
  const double g =
      std::max({b.row(0).norm(), b.row(1).norm(), b.row(2).norm(), b.colwise().sum().norm()});
  return e.volume[k] * (e.lame.lambda + 2 * e.lame.mu) * g;
}

// The batched loop's forces `f` on the separated elements against the one-element kernel's, one
// element's forces `g` at a time, each component relative to that element's unit-strain force:
// `worst` the largest difference, `largest` the largest force.
struct KernelAgreement {
  double worst = 0, largest = 0;
  void add(const Separated& s, const Eigen::Matrix3Xd& f, int k, const double (&g)[4][3]) {
    const double scale = unit_strain_force(s.e, k);
    for (int a = 0; a < 4; ++a) {
      for (int c = 0; c < 3; ++c) {
        worst = std::max(worst, std::abs(f(c, 4 * k + a) - g[a][c]) / scale);
        largest = std::max(largest, std::abs(g[a][c]) / scale);
      }
    }
  }
};

// What both laws' batched loops must do on the strained ball: report the inverted element the
// kernel found first, sum the same energy to 1e-12 relative, and give the kernel's forces to 1e-12
// of the unit-strain force, forces that are strains' worth (> 1e-3), not round-off (why these
// tolerances: test_neo_hookean_tet.cpp).
inline void expect_batched_equals_kernel(const InternalForceResult& r, double energy, int inverted,
                                         const KernelAgreement& forces) {
  ASSERT_GE(inverted, 0);
  EXPECT_EQ(r.inverted, inverted);
  EXPECT_LE(std::abs(r.energy - energy), 1e-12 * energy);
  EXPECT_LE(forces.worst, 1e-12);
  EXPECT_GT(forces.largest, 1e-3);
}

}  // namespace asperity::fem::test_material
