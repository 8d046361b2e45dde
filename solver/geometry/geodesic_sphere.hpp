// The geodesic icosphere: a closed, outward, nearly uniform triangulation of the unit sphere.
#pragma once

#include "solver/core/mesh.hpp"

namespace asperity::geometry {

// Each face of the regular icosahedron split into n² triangles (frequency n), every vertex
// projected onto the unit sphere: 20 n² faces, 10 n² + 2 vertices, edge length ≈ 1.1/n.
// Its enclosed volume converges to 4π/3 with error O(n⁻²) (chord error of a sphere, h²/(8R)).
SurfaceMesh geodesic_sphere(int n);

}  // namespace asperity::geometry
