// Checking a triangle surface (closed, 2-manifold, one shell, outward, no self-intersections,
// positive volume) and the safe repairs that turn a scanner's polygon soup into one.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "solver/core/mesh.hpp"
#include "solver/geometry/read_mesh.hpp"

namespace asperity::geometry {

// Every change made to the input, in words, in the order made (mesh.json "repairs"), and what
// the user should know but that did not change the geometry's meaning (mesh.json "warnings").
struct MeshLog {
  std::vector<std::string> repairs;
  std::vector<std::string> warnings;
};

// Diagnostics of a triangle surface; counts, so that messages and tests can name them.
struct MeshCheck {
  long faces = 0, vertices = 0;
  long border_edges = 0;          // edges in exactly one face (holes)
  long nonmanifold_edges = 0;     // edges in more than two faces
  long nonmanifold_vertices = 0;  // vertices whose faces form more than one fan
  long misoriented_edges = 0;     // two-face edges both faces traverse in the same direction
  long degenerate_faces = 0;      // repeated vertex or three collinear points (exact predicate)
  long shells = 0;                // edge-connected components
  long self_intersections = -1;   // intersecting pairs of non-adjacent faces; −1: not checked
  double volume = 0;              // signed, m³ (divergence theorem)

  bool closed() const { return border_edges == 0 && nonmanifold_edges == 0; }
  bool manifold() const { return nonmanifold_edges == 0 && nonmanifold_vertices == 0; }
  // Closed, manifold, one shell, consistently and outwardly oriented, no degenerate face, no
  // self-intersection (when checked).
  bool valid() const {
    return closed() && manifold() && shells == 1 && misoriented_edges == 0 &&
           degenerate_faces == 0 && self_intersections <= 0 && volume > 0;
  }
};

MeshCheck check_mesh(const SurfaceMesh& mesh, bool self_intersections = true);

// Shells smaller than this fraction of the largest shell's volume are dropped with a warning
// (scanner debris, trapped inner bubbles); a larger second shell is refused.
inline constexpr double kTinyShellFraction = 1e-2;

// Repairs that cannot change the intended solid, each recorded in `log`: fan-triangulate
// polygons, merge vertices with identical coordinates, drop unreferenced vertices, drop faces
// with a repeated vertex and duplicate faces, orient every shell consistently, drop tiny shells,
// flip an inward-wound mesh, remove zero-area faces by collapsing them. Everything else is refused
// with InputError "NAME: defect: count ..." (open, non-manifold edge or vertex, non-orientable,
// several shells, zero volume, self-intersecting). `name` is the file, for the message.
SurfaceMesh repair_mesh(const PolygonSoup& soup, const std::string& name, MeshLog& log);

// read_mesh_file + repair_mesh.
SurfaceMesh load_surface_mesh(const std::filesystem::path& file, const ReadOptions& options,
                              MeshLog& log);

}  // namespace asperity::geometry
