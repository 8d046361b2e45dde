// Removing the edges far shorter than their neighbours that edge-collapse simplification leaves
// behind, keeping the triangle count (issue 11, item 5).
#pragma once

#include "solver/core/mesh.hpp"

namespace asperity::geometry {

// How much shorter than its neighbours an edge may be, and what was done about it.
struct ShortEdgeOptions {
  // An edge is short when its length is below this fraction of the mean length of the other
  // edges at its two end vertices. The shortest surface edge h sets the step a surface of that
  // resolution calls for (h/c); an edge a few times shorter than its ring makes h a leftover of
  // the simplification rather than the mesh's resolution (reports/fem/mesh_step.md). 0.1: below
  // every edge of the default study's 20 meshes (least 0.102, so they are unchanged) and above
  // the leftover that broke the step bound (ballast_09 at 1000 faces: 0.048).
  double ratio = 0.1;
  // Collapses at most this many edges (each followed by one bisection).
  int max_collapses = 100;
};

struct ShortEdgeRepair {
  int short_edges = 0;  // edges below the ratio before the repair
  int collapsed = 0;    // of them collapsed (the others failed a check below)
  // |V − V₀| / V₀ after the repair (round-off: the placement keeps the volume).
  double volume_change_rel = 0;
};

// Collapses each short edge (shortest relative to its ring first) to one vertex at the point
// nearest the edge's midpoint that keeps the enclosed volume: the volume is linear in that point,
// so the constraint is a plane and the point its projection (the first of Lindstrom & Turk's
// 1998 placement constraints, which the simplification itself keeps). A collapse is made only
// when it keeps the surface a closed 2-manifold (the link condition: the two end vertices share
// exactly the two opposite vertices), turns no remaining face over (normal change < 90°, as the
// simplification's own filter), moves the vertex less than the edge's length from the midpoint,
// and leaves no edge at the new vertex shorter than the one removed. Each collapse removes two
// triangles; the longest edge of the surface is then bisected at its midpoint, which lies in the
// plane of both its triangles, so the triangle count is the input's again and the bisection
// changes no area, volume or centroid. A surface with no short edge is returned unchanged (bit
// for bit). `mesh`: closed, manifold, outward.
ShortEdgeRepair remove_short_edges(SurfaceMesh& mesh, const ShortEdgeOptions& options = {});

}  // namespace asperity::geometry
