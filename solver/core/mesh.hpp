// Plain mesh data shared by the geometry pipeline (which makes them) and the FEM/DEM core
// (which runs them). SI units; no CGAL here.
#pragma once

#include <Eigen/Core>

namespace asperity {

// A closed triangle surface, faces counter-clockwise seen from outside (outward normals).
struct SurfaceMesh {
  Eigen::Matrix3Xd vertices;  // m
  Eigen::Matrix3Xi faces;     // vertex indices
};

// Linear tetrahedra with positive volume ((b−a)×(c−a))·(d−a) > 0; `surface` holds the boundary
// triangles (outward) as node indices, exactly the surface mesh that was tetrahedralized.
struct TetMesh {
  Eigen::Matrix3Xd nodes;    // m
  Eigen::Matrix4Xi tets;     // node indices
  Eigen::Matrix3Xi surface;  // node indices
};

}  // namespace asperity
