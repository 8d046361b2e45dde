// A contact-local surface (issue 28): the particle's own source triangles kept exactly around its
// strike point and simplified far from it, so that a refined reference resolves the contact on
// the particle itself rather than on a simplification of it.
#pragma once

#include "solver/core/mesh.hpp"
#include "solver/core/vec.hpp"

namespace asperity::geometry {

struct ContactPatch {
  Vec3 centre = Vec3::Zero();  // the strike point, m (the source's coordinates)
  double radius = 0;           // m: every source triangle with all vertices within it is kept
  // The rest of the surface is simplified to the density of a particle of this many triangles:
  // far_faces × (the share of the source's triangles outside the patch), rounded to even.
  long far_faces = 2000;
};

struct ContactLocalSurface {
  SurfaceMesh surface;    // closed, manifold, outward (as the source)
  long kept_faces = 0;    // source triangles within the patch, kept bit for bit
  long source_faces = 0;  // the source's triangle count
};

// Simplifies `source` (closed, manifold, outward: as repair_mesh returns it) by the edge collapse
// of simplify_edge_collapse (Lindstrom–Turk cost and placement, which keep the enclosed volume
// at every collapse, and the bounded-normal-change filter), with every edge that has an end vertex
// within the patch constrained: CGAL collapses no constrained edge and no edge between two
// vertices of constrained edges, so no vertex within the patch moves and every triangle with all
// three vertices within it is the source's, bit for bit. The short-edge finish of
// simplify_edge_collapse is not applied: it would move the patch's vertices; far from the patch
// the graded element size of a refined case bisects the surface again near the strike point.
// A collapse is also refused when it would leave a face thinner than kContactLocalThinFace (its
// height over its longest edge) where the face it replaces was not as thin: no vertex of the
// patch moves, so the collapses next to it do all the simplifying there and, unfiltered, left
// folds at the patch's edge (rock_04: a face of height 0.0019 R against a longest edge of 0.30 R,
// its neighbours at 93-95 degrees) whose thin tetrahedra set a refined case's step: its a/3 level
// ran at 3.6 ns and 197 730 steps, at 26.2 ns and 27 342 steps with the filter; rock_02's three
// levels at 9.4 ns whatever their size (docs/study.md, "The source reference"). So every face of
// the result is at least min(kContactLocalThinFace, the source's thinnest) thick.
// A patch holding the whole surface, or a far target at or above the source's count, returns
// the source unchanged. std::runtime_error when the collapses stop short of the target.
inline constexpr double kContactLocalThinFace = 0.05;
ContactLocalSurface contact_local_surface(const SurfaceMesh& source, const ContactPatch& patch);

// A face's thickness: its height over its longest edge, 2 A / L² (√3/2 for an equilateral
// triangle, 0 for a degenerate one).
double face_thickness(const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace asperity::geometry
