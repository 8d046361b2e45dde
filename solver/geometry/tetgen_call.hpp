// One TetGen 1.5 run (Si 2015, ACM TOMS 41(2):11) on a closed surface, and the same run in a
// child process under a time budget. tetrahedralize.cpp builds the jobs (lifting rounds, element
// size); this file only talks to TetGen.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "solver/core/mesh.hpp"
#include "solver/core/vec.hpp"

namespace asperity::geometry {

struct TetgenJob {
  SurfaceMesh surface;
  // Interior points kept as nodes right after the surface vertices (lift apexes), and triangles
  // over all those points kept as internal facets (lift walls).
  std::vector<Vec3> extra_points;
  std::vector<std::array<int, 3>> internal_facets;
  // Target size at every input point (surface vertices, then extra points), m; TetGen's "m"
  // switch refines while a tetrahedron's circumradius exceeds the size interpolated at it.
  // Empty: no size control.
  std::vector<double> point_sizes;
  double radius_edge_ratio = 0;  // "q" bound, 0: none
  double min_dihedral_deg = 0;   // with q: "q ratio/angle", 0: TetGen's default
  long max_steiner_points = -1;  // "S" budget of interior points, < 0: unbounded
};

// Switches "pYzQ" (+ "q…", "m", "S…"): p reads the surface as a piecewise linear complex, Y
// forbids Steiner points on it, so the boundary of the result is exactly the input triangles
// (checked). Nodes: the surface vertices, then the extra points, in their order (checked), then
// TetGen's interior points; tetrahedra positively oriented; `surface` the input faces. Throws
// std::runtime_error when TetGen fails (its reason in words) or breaks a promise above.
TetMesh run_tetgen(const TetgenJob& job);

// Interior points TetGen added in `mesh` for `job` (beyond surface and extra points).
long steiner_points(const TetgenJob& job, const TetMesh& mesh);

// run_tetgen in a child process. Debian's TetGen keeps its internal assert()s, and some inputs
// trip one during facet recovery (e.g. removeedgebyflips on a 2000-triangle ballast particle
// with lift walls): abort() would end the whole program, a study included. Quality refinement
// with an unattainable bound never ends (issue 18): the child is killed after `seconds` of wall
// time. The child sends the mesh back through a pipe. Its user + system CPU, which no clock of
// the calling thread sees, is added to the thread's waited_children_cpu_seconds (core/clock.hpp).
struct IsolatedResult {
  std::optional<TetMesh> mesh;
  bool timed_out = false;
  std::string failure;  // why mesh is empty: TetGen's reason, a signal, or the time budget
};
IsolatedResult run_tetgen_isolated(const TetgenJob& job, double seconds);

// The failed check of an assert() message on TetGen's stderr, for the one line of a failure:
// "tetgen: /path/tetgen.cxx:11026: int tetgenmesh::locate(...): Assertion `x' failed." gives
// ": tetgen.cxx:11026, in tetgenmesh::locate, `x'"; "" when the text holds none.
std::string tetgen_assertion(const std::string& stderr_text);

}  // namespace asperity::geometry
