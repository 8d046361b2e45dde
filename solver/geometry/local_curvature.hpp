// The principal radii of curvature of a closed surface at its lowest vertex (where a particle
// falling straight down first touches a flat block), from a quadric fitted to the vertices of a
// small patch around it. The study's "sphere-local" model (docs/study.md) is Hertz's sphere of
// the equivalent radius √(R1 R2) there (Johnson 1985, "Contact Mechanics", §4.2: an elliptical
// contact behaves, to first order in its ellipticity, like a circular one of that radius).
#pragma once

#include "solver/core/mesh.hpp"
#include "solver/core/vec.hpp"

namespace asperity::geometry {

struct LocalCurvature {
  Vec3 point = Vec3::Zero();  // the lowest vertex (m)
  // Principal curvatures κ1 ≤ κ2 (1/m; positive where the surface bulges towards −z) and the
  // radii 1/κ (m; infinite where κ ≤ 0).
  double curvature_min = 0, curvature_max = 0;
  double radius_min = 0, radius_max = 0;
  int samples = 0;          // vertices in the fitted patch, the lowest one included
  double patch_radius = 0;  // m, the patch's radius as used
  bool convex() const { return curvature_min > 0; }
  // √(R1 R2) where convex; else 1/κ2 where κ2 > 0 (a ridge: the contact is a line's, taken as
  // the sharper direction's circle); else 0 (flat or concave: no Hertz sphere).
  double equivalent_radius() const;
};

// The mean edge length of the surface (m).
double mean_edge_length(const SurfaceMesh& surface);

// Fits w = c0 + c1 x + c2 y + a x² + b xy + c y² (w the height above the lowest vertex, x, y
// horizontal) by least squares to every vertex within `patch_radius` of the lowest vertex, and
// takes the principal curvatures of that graph at the lowest vertex (shape operator of a graph
// with slope g: (I + g gᵀ)⁻¹ H / √(1 + |g|²)). The patch grows by 1.5× until it holds at least
// 10 vertices (6 unknowns). On vertices exactly on a smooth surface whose lowest point is a
// vertex, the error of each radius falls at second order with the edge (the fit's residual is
// the surface's quartic term over a patch that shrinks with it): 3.2, 0.79, 0.18, 0.05 % on an
// ellipsoid at icosphere frequencies 8–64 (tests/geometry/test_local_curvature.cpp).
LocalCurvature lowest_point_curvature(const SurfaceMesh& surface, double patch_radius);

}  // namespace asperity::geometry
