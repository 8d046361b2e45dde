// TetGen call that keeps the surface triangles (issue 3, "Tetrahedralization"); the switches and
// their reasons are in the header. TetGen is built as a library (TETLIBRARY): it throws an int.
#define TETLIBRARY
#include "geometry/tetrahedralize.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <tetgen.h>

#include "core/error.hpp"
#include "core/vec.hpp"

namespace asperity::geometry {
namespace {

std::string tetgen_error(int code) {
  switch (code) {
    case 1:
      return "out of memory";
    case 2:
      return "internal error";
    case 3:
      return "the surface intersects itself";
    case 4:
      return "a feature of the surface is below TetGen's tolerance (very small)";
    case 5:
      return "two surface faces are too close to each other";
    case 10:
      return "invalid input";
    default:
      return "error code " + std::to_string(code);
  }
}

// Faces of the tetrahedra that belong to one tetrahedron only, as sorted triples.
std::vector<std::array<int, 3>> boundary_faces(const Eigen::Matrix4Xi& tets) {
  static constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  std::vector<std::array<int, 3>> all;
  all.reserve(4 * static_cast<std::size_t>(tets.cols()));
  for (Eigen::Index t = 0; t < tets.cols(); ++t)
    for (const auto& f : kFace) {
      std::array<int, 3> tri{tets(f[0], t), tets(f[1], t), tets(f[2], t)};
      std::sort(tri.begin(), tri.end());
      all.push_back(tri);
    }
  std::sort(all.begin(), all.end());
  std::vector<std::array<int, 3>> once;
  for (std::size_t i = 0; i < all.size();) {
    std::size_t j = i;
    while (j < all.size() && all[j] == all[i]) ++j;
    if (j - i == 1) once.push_back(all[i]);
    i = j;
  }
  return once;
}

}  // namespace

TetMesh tetrahedralize(const SurfaceMesh& surface, const TetOptions& options) {
  const int n = static_cast<int>(surface.vertices.cols());
  const int nf = static_cast<int>(surface.faces.cols());
  tetgenio in, out;
  in.firstnumber = 0;
  in.numberofpoints = n;
  in.pointlist = new REAL[3 * static_cast<std::size_t>(n)];
  std::memcpy(in.pointlist, surface.vertices.data(),
              sizeof(REAL) * 3 * static_cast<std::size_t>(n));
  in.numberoffacets = nf;
  in.facetlist = new tetgenio::facet[static_cast<std::size_t>(nf)];
  for (int i = 0; i < nf; ++i) {
    tetgenio::facet& f = in.facetlist[i];
    tetgenio::init(&f);
    f.numberofpolygons = 1;
    f.polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&f.polygonlist[0]);
    f.polygonlist[0].numberofvertices = 3;
    f.polygonlist[0].vertexlist =
        new int[3]{surface.faces(0, i), surface.faces(1, i), surface.faces(2, i)};
  }
  std::ostringstream sw;
  sw << "pYzQ";
  if (options.radius_edge_ratio > 0) {
    sw << "q" << options.radius_edge_ratio;
    if (options.min_dihedral_deg > 0) sw << "/" << options.min_dihedral_deg;
  }
  std::string switches = sw.str();
  try {
    ::tetrahedralize(switches.data(), &in, &out);
  } catch (int code) {
    throw std::runtime_error("TetGen failed (switches " + switches + "): " + tetgen_error(code));
  }
  ASPERITY_CHECK(out.numberofcorners == 4 && out.numberofpoints >= n);

  TetMesh tm;
  tm.nodes = Eigen::Map<const Eigen::Matrix3Xd>(out.pointlist, 3, out.numberofpoints);
  if (tm.nodes.leftCols(n) != surface.vertices) {
    throw std::runtime_error("TetGen reordered or moved the surface vertices (switches " +
                             switches + ")");
  }
  tm.tets = Eigen::Map<const Eigen::Matrix4Xi>(out.tetrahedronlist, 4, out.numberoftetrahedra);
  for (Eigen::Index t = 0; t < tm.tets.cols(); ++t) {
    const Eigen::Vector3d a = tm.nodes.col(tm.tets(0, t));
    const double six_v = (tm.nodes.col(tm.tets(1, t)) - a)
                             .cross(tm.nodes.col(tm.tets(2, t)) - a)
                             .dot(tm.nodes.col(tm.tets(3, t)) - a);
    if (six_v < 0) std::swap(tm.tets(2, t), tm.tets(3, t));
  }
  tm.surface = surface.faces;

  // The promise of switch Y, checked: the tetrahedra's boundary is the input triangles.
  std::vector<std::array<int, 3>> input(static_cast<std::size_t>(nf));
  for (int i = 0; i < nf; ++i) {
    input[i] = {surface.faces(0, i), surface.faces(1, i), surface.faces(2, i)};
    std::sort(input[i].begin(), input[i].end());
  }
  std::sort(input.begin(), input.end());
  if (boundary_faces(tm.tets) != input) {
    throw std::runtime_error("TetGen changed the surface triangles (switches " + switches + ")");
  }
  return tm;
}

}  // namespace asperity::geometry
