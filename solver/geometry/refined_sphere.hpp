// A sphere refined towards its strike point: the Hertz scenes' particle (scenes/hertz_spheres.hpp)
// and the study's sphere-like particle (tests/study/test_sphere_study.cpp).
#pragma once

#include "solver/core/mesh.hpp"
#include "solver/core/vec.hpp"

namespace asperity::geometry {

// The geodesic icosphere of `frequency` (geodesic_sphere) scaled to `radius`, its facets
// bisected (subdivide_surface, longest edge first) down to `edge` within `patch` of `focus`,
// every new vertex put back on the sphere after each pass, until a pass splits nothing. The
// bisection alone would keep the coarse facets' planes (a faceted sphere however fine the
// facets); projecting the vertices makes the fine patch a sphere to the chord error e²/(8R) of
// its own edges, which is what a Hertz contact of radius a ≫ e sees.
SurfaceMesh refined_sphere(int frequency, double radius, double edge, double patch,
                           const Vec3& focus);

// The vertex with the smallest z (the first when several tie): where the study's "lowest"
// placement puts a particle's contact.
Vec3 lowest_vertex(const SurfaceMesh& surface);

}  // namespace asperity::geometry
