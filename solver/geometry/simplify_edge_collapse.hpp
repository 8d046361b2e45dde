// Simplifying a closed triangle surface to exactly N triangles by edge collapse.
#pragma once

#include <string>

#include "solver/core/mesh.hpp"

namespace asperity::geometry {

// Collapses edges of `mesh` (closed, manifold, outward; as repair_mesh returns it) until it has
// exactly `faces` triangles, with CGAL's Surface_mesh_simplification:
//  - cost and placement: Lindstrom–Turk (Lindstrom & Turk 1998, "Fast and memory efficient
//    polygonal simplification"; 1999 "Evaluation of memoryless simplification"). Its placement
//    keeps the enclosed volume unchanged to first order at every collapse and then minimises the
//    change in shape, so the volume change the study reports stays small and what is lost is
//    the fine shape: a sharp asperity is blunted and its volume spread over its neighbourhood,
//    which is what the shape metrics (shape_metrics.hpp) measure. Garland–Heckbert quadrics
//    would keep sharp corners longer but let the volume drift with every collapse.
//  - filter: Bounded_normal_change_filter rejects a collapse that would turn any neighbouring
//    face over (normal change ≥ 90°), so the result stays an embedded, outward surface.
//  - stop: each collapse of an edge of a closed triangle mesh removes 1 vertex, 3 edges and 2
//    faces; 3F = 2E, so stopping at E = 3N/2 edges gives exactly N faces.
//  - finish: the collapses can leave an edge far shorter than the edges around it (a sharp
//    corner the placement kept; ballast_09 of the study at 1000 faces: 0.048 of its ring's
//    mean length). The shortest surface edge h is what a surface of that resolution calls for (h/c,
//    issue 11, item 5); such an edge is a leftover, not the resolution. Every edge shorter than
//    ShortEdgeOptions::ratio (0.1) × the mean of the other edges at its two vertices is collapsed
//    where that is valid and the triangle count restored by bisecting the longest edge
//    (remove_short_edges.hpp: volume kept, no face turned over, still a closed 2-manifold). A
//    surface with no such edge is the edge collapse's result unchanged.
// A closed triangle surface always has an even number of faces (3F = 2E; for one shell of genus
// 0, F = 2V − 4), so N must be even, ≥ 4 and ≤ the input's count; otherwise InputError. When a
// collapse blocked by the filter leaves more than N faces, std::runtime_error. N equal to the
// input's count returns the input unchanged.
SurfaceMesh simplify_edge_collapse(const SurfaceMesh& mesh, long faces);

// The InputError message simplify_edge_collapse gives for an impossible target, or "" when
// `faces` is possible for a closed mesh of `input_faces` triangles (for early checks).
std::string face_target_problem(long faces, long input_faces);

}  // namespace asperity::geometry
