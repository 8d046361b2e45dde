// Tetrahedralizing the solid a closed triangle surface bounds, keeping those triangles exactly.
#pragma once

#include "core/mesh.hpp"

namespace asperity::geometry {

struct TetOptions {
  // TetGen's quality bound "q": largest circumradius-to-shortest-edge ratio of a tetrahedron,
  // met by inserting points inside the solid only (never on the surface, switch Y). 0 turns
  // quality refinement off (a constrained Delaunay tetrahedralization of the surface points
  // only). 2 is TetGen's own default bound; tighter bounds add many interior points near
  // poorly shaped surface triangles.
  double radius_edge_ratio = 2.0;
  // Also asked of TetGen with q (its "q ratio/angle" form): smallest dihedral angle, degrees.
  // 0 leaves TetGen's default. Interior refinement cannot fix a sliver touching the surface.
  double min_dihedral_deg = 0;
};

// Constrained Delaunay tetrahedralization with TetGen 1.5 (Si 2015, ACM TOMS 41(2):11), switches
// "pYzQ" (+ "q" when asked): p reads the surface as a piecewise linear complex, Y forbids
// Steiner points on it, so the boundary of the result is exactly the input triangles. The
// result's nodes begin with the surface vertices in their order (checked), its tetrahedra have
// positive orientation ((b−a)×(c−a))·(d−a) > 0, and `surface` is the input's face array.
// Throws std::runtime_error when TetGen fails (its reason in words) or when the boundary of the
// result differs from the input triangles.
TetMesh tetrahedralize(const SurfaceMesh& surface, const TetOptions& options = {});

}  // namespace asperity::geometry
