// Broad phase for FEM/DEM contact: candidate pairs of surface tetrahedra of different bodies.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "solver/fdem/fdem_world.hpp"

namespace asperity::fdem {

// Every pair (a < b) of tetrahedra of different bodies, not both on fixed bodies, whose
// axis-aligned boxes grown by margin/2 on every side overlap, sorted by (a, b). Bodies first: a
// sort and sweep over the bodies' boxes finds the pairs of bodies that meet; for each, the
// tetrahedra of either inside the other's box are swept against each other (Baraff 1992) with one
// active list per body, so two tetrahedra of the same body are never compared:
// O(n log n + k) for n tetrahedra and k pairs of overlapping intervals across bodies. (One sweep
// over all tetrahedra also visits the same-body pairs, O(n²) for a convex hull's long tetrahedra:
// docs/physics.md, "Overlap geometry".) Because each box grows by margin/2, the list stays
// complete until some node has moved margin/2.
std::vector<TetPair> candidate_pairs(const Eigen::Matrix3Xd& x, const Eigen::Matrix4Xi& tets,
                                     const std::vector<int>& tet_body,
                                     const std::vector<std::uint8_t>& body_fixed, double margin);

}  // namespace asperity::fdem
