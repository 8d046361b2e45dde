// Tetrahedral meshes of simple solids, built in code: boxes (fixed blocks, test bars) and a
// cube-mapped ball (tests and benchmarks without the geometry pipeline).
#pragma once

#include "solver/core/mesh.hpp"
#include "solver/core/vec.hpp"

namespace asperity::fdem {

// Boundary triangles of a tetrahedral mesh (faces used by exactly one element), outward.
Eigen::Matrix3Xi boundary_faces(const Eigen::Matrix4Xi& tets);

// Axis-aligned box [lo, hi] split into nx × ny × nz cells of 6 tetrahedra each (Freudenthal–Kuhn:
// every cell cut along the same diagonal, so the mesh is conforming).
TetMesh box_mesh(const Vec3& lo, const Vec3& hi, int nx, int ny, int nz);

// The same box mesh with its corners placed by a rotation `frame` (columns: the box's axes)
// about `origin`: x = origin + frame · local, local in [lo, hi].
TetMesh oriented_box_mesh(const Vec3& origin, const Mat3& frame, const Vec3& lo, const Vec3& hi,
                          int nx, int ny, int nz);

// A ball of radius r centred at the origin: the box mesh of [−1, 1]³ with n cells per side,
// mapped onto the ball by the elliptical cube-to-sphere map x' = x √(1 − y²/2 − z²/2 + y²z²/3)
// (and cyclically), which keeps element volumes positive and the surface on the sphere.
TetMesh ball_mesh(double r, int n);

}  // namespace asperity::fdem
