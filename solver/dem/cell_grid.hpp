// Broad phase for spheres: a uniform cell grid giving the Verlet neighbour list.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "solver/dem/sphere_world.hpp"

namespace asperity::dem {

// Every pair (i < j) whose gap is below `skin`, except fixed–fixed pairs, sorted by (i, j).
// Cost O(N) for a packing: cells of edge 2 r_max + skin, each sphere against 27 cells.
std::vector<PairContact> neighbour_pairs(const Eigen::Matrix3Xd& x,
                                         const std::vector<double>& radius,
                                         const std::vector<std::uint8_t>& fixed, double skin);

}  // namespace asperity::dem
