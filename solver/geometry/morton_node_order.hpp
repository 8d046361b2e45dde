// Node numbering along a Morton (Z-order) curve, for memory locality of the element loop.
//
// The element loop (fem/internal_forces.cpp) gathers each element's four nodes and scatters its
// forces back to them. A pipeline mesh numbers its nodes as they were made (the source's vertices,
// then the bisected surface's, then TetGen's Steiner points in insertion order), scattered over
// the body, so consecutive elements touch nodes far apart in memory. Numbered along a Z-order curve
// of their positions, nodes close in space are close in memory. The elements keep their order, so
// every node receives its element forces in the same sequence as before: the forces, and every
// result built from them, are the same to the bit (tests/geometry/test_morton_node_order.cpp).
// Measured on a source-reference level of 45 327 tetrahedra (docs/performance.md, "Nodes along a
// Morton curve"): the element loop 1.18 times faster. Used on the deformable bodies' meshes a run
// builds its world from (run::mesh_body); the pipeline's own meshes keep their surface's vertices
// first.
#pragma once

#include <vector>

#include "solver/core/mesh.hpp"
#include "solver/core/vec.hpp"

namespace asperity::geometry {

// The new number of each node of `nodes` (new_index[old] = new): nodes sorted by the Morton code
// of their position quantised to 2²¹ cells per axis of the bounding cube; nodes in one cell keep
// their relative order.
std::vector<int> morton_node_order(const Eigen::Matrix3Xd& nodes);

// Renumbers m's nodes by morton_node_order: the tetrahedra and surface triangles refer to the same
// points, in the same order.
void number_nodes_along_morton_curve(TetMesh& m);

}  // namespace asperity::geometry
