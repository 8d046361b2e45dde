// The state both element laws' batched-loop tests run (test_neo_hookean_tet.cpp,
// test_linear_elastic_tet.cpp): a ball mesh's nodes moved by a deterministic 1 % jiggle, with
// element 100 turned inside out (its fourth node reflected through its first), so the loop must
// both compute and report an inverted element.
#pragma once

#include <cmath>

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

}  // namespace asperity::fem::test_material
