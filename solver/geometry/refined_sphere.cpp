// A sphere refined towards its strike point (refined_sphere.hpp).
#include "solver/geometry/refined_sphere.hpp"

#include "solver/geometry/element_size.hpp"
#include "solver/geometry/geodesic_sphere.hpp"

namespace asperity::geometry {

SurfaceMesh refined_sphere(int frequency, double radius, double edge, double patch,
                           const Vec3& focus) {
  SurfaceMesh s = geodesic_sphere(frequency);
  s.vertices *= radius;
  // growth 1: beyond the patch the size grows by the distance, so the splitting fades out within
  // about a coarse edge of it.
  const ElementSize fine{.size = edge, .focus = focus, .focus_radius = patch, .growth = 1.0};
  for (Eigen::Index before = -1; before != s.faces.cols();) {
    before = s.faces.cols();
    s = subdivide_surface(s, fine);
    for (Eigen::Index i = 0; i < s.vertices.cols(); ++i)
      s.vertices.col(i) *= radius / s.vertices.col(i).norm();
  }
  return s;
}

Vec3 lowest_vertex(const SurfaceMesh& surface) {
  Eigen::Index low = 0;
  for (Eigen::Index i = 1; i < surface.vertices.cols(); ++i) {
    if (surface.vertices(2, i) < surface.vertices(2, low)) low = i;
  }
  return surface.vertices.col(low);
}

}  // namespace asperity::geometry
