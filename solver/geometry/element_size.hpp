// Element size apart from surface geometry (issue 11): the target tetrahedron edge length as a
// field over space, the surface subdivided in its own planes to meet it, and the estimate of the
// tetrahedron count it implies (checked before any meshing).
#pragma once

#include <limits>
#include <string>

#include "solver/core/mesh.hpp"
#include "solver/core/vec.hpp"

namespace asperity::geometry {

// Target edge length, m, at a point: `size` within `focus_radius` of `focus`, growing linearly
// with distance beyond it at `growth` (m of size per m of distance), capped at `far`. With
// growth 0 (the default) the size is `size` everywhere (uniform). A grading rate of 0.2–0.3
// keeps neighbouring tetrahedra within a few per cent of each other's size, so the quality
// mesher needs no transition layers (Frey & George 2008, "Mesh generation", §1.4 on size maps).
struct ElementSize {
  double size = 0;  // m, > 0 when set
  Vec3 focus = Vec3::Zero();
  double focus_radius = 0;                               // m
  double growth = 0;                                     // dimensionless, 0: uniform
  double far = std::numeric_limits<double>::infinity();  // m, the largest size
  bool set() const { return size > 0; }
  double at(const Vec3& x) const;
};

// Longest-edge bisection (Rivara 1984, Int. J. Numer. Meth. Eng. 20:745–756) of a closed surface
// until every edge is at most the target size at its midpoint. Each split puts a vertex at an
// edge's midpoint, which lies in the plane of both triangles that share the edge, so the surface
// (area, enclosed volume, centroid) is unchanged to round-off, and a triangle is split across
// its longest edge only (its neighbour first, where that edge is not the neighbour's longest:
// the longest-edge propagation path), so the smallest angle stays at least half the input's.
// Vertices keep their indices; new ones follow. `max_faces` bounds the result (InputError
// naming the count if it would be passed).
SurfaceMesh subdivide_surface(const SurfaceMesh& surface, const ElementSize& size,
                              long max_faces = 40'000'000);

// Tetrahedra a quality mesh of this size field would have for the solid, from its volume and
// the size at each tetrahedron of a coarse grid: a regular tetrahedron of edge h has volume
// h³/(6√2), and quality meshes run about 1.5× that count (Delaunay refinement packs
// non-regular elements; measured on the gate spheres, docs/geometry.md).
double estimated_tets(const SurfaceMesh& surface, const ElementSize& size);

// The reason an element size cannot be used for this surface, or "" when it can: not finite or
// ≤ 0, larger than the particle (its longest bounding-box extent), or more than `max_tets`
// estimated tetrahedra. The message names the value and the estimated count.
std::string element_size_problem(const SurfaceMesh& surface, const ElementSize& size,
                                 double max_tets = 20e6);

}  // namespace asperity::geometry
