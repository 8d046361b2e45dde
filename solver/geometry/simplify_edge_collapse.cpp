// Edge-collapse simplification to an exact triangle count (issue 3, "Simplification"); the
// choice of policies and why is in the header.
#include "solver/geometry/simplify_edge_collapse.hpp"

#include <stdexcept>

#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Bounded_normal_change_filter.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/LindstromTurk_cost.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/LindstromTurk_placement.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include "solver/core/error.hpp"
#include "solver/geometry/cgal_surface_mesh.hpp"
#include "solver/geometry/remove_short_edges.hpp"

namespace asperity::geometry {

std::string face_target_problem(long faces, long input_faces) {
  if (faces < 4)
    return "faces must be at least 4, a tetrahedron (got " + std::to_string(faces) + ")";
  if (faces % 2 != 0) {
    return "faces must be even: every closed triangle surface has an even number of triangles "
           "(3F = 2E), and each edge collapse removes two (got " +
           std::to_string(faces) + ")";
  }
  if (faces > input_faces) {
    return "faces " + std::to_string(faces) + " is more than the input's " +
           std::to_string(input_faces) + " triangles; simplification only removes triangles";
  }
  return "";
}

SurfaceMesh simplify_edge_collapse(const SurfaceMesh& mesh, long faces) {
  namespace SMS = CGAL::Surface_mesh_simplification;
  const long input_faces = static_cast<long>(mesh.faces.cols());
  if (const std::string problem = face_target_problem(faces, input_faces); !problem.empty()) {
    throw InputError(problem);
  }
  if (faces == input_faces) return mesh;
  cgal::Mesh cm = cgal::to_cgal(mesh);
  ASPERITY_CHECK(static_cast<long>(cm.number_of_faces()) == input_faces && CGAL::is_closed(cm));
  // Stops once fewer than 3N/2 + 1 edges remain, i.e. at exactly 3N/2 edges (steps of 3).
  const SMS::Count_stop_predicate<cgal::Mesh> stop(static_cast<std::size_t>(3 * faces / 2 + 1));
  const SMS::Bounded_normal_change_filter<> filter;
  SMS::edge_collapse(cm, stop,
                     CGAL::parameters::get_cost(SMS::LindstromTurk_cost<cgal::Mesh>())
                         .get_placement(SMS::LindstromTurk_placement<cgal::Mesh>())
                         .filter(filter));
  cm.collect_garbage();
  const long got = static_cast<long>(cm.number_of_faces());
  if (got != faces) {
    throw std::runtime_error("edge collapse stopped at " + std::to_string(got) +
                             " triangles, not the " + std::to_string(faces) +
                             " asked for: the remaining collapses would fold faces over");
  }
  SurfaceMesh out = cgal::from_cgal(cm);
  remove_short_edges(out);
  return out;
}

}  // namespace asperity::geometry
