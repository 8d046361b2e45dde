// Size and quality numbers of a tetrahedral mesh: what the FEM time step and accuracy depend on.
#pragma once

#include "solver/core/mesh.hpp"

namespace asperity::geometry {

struct TetQuality {
  long tets = 0;
  long nodes = 0;
  long interior_nodes = 0;      // nodes not on the surface (TetGen's interior Steiner points)
  double volume_sum = 0;        // Σ tetrahedron volumes, m³
  double min_volume = 0;        // smallest tetrahedron volume, m³ (> 0 for a valid mesh)
  double min_dihedral_deg = 0;  // smallest dihedral angle over all tetrahedra, degrees
  double max_dihedral_deg = 0;  // largest, degrees
  double smallest_edge = 0;     // shortest tetrahedron edge, m: sets the FEM critical step
  double longest_edge = 0;      // longest tetrahedron edge, m
  // Largest circumradius / shortest edge over the tetrahedra (TetGen's q measure; √6/4 ≈ 0.61
  // for the regular tetrahedron, unbounded for slivers).
  double max_radius_edge_ratio = 0;
};

// Dihedral angle at edge (i, j) of a tetrahedron: the angle between the other two vertices'
// offsets projected onto the plane normal to the edge.
TetQuality tet_quality(const TetMesh& mesh);

}  // namespace asperity::geometry
