// Shape metrics against the source mesh (issue 3, "Shape metrics"); definitions in the header.
#include "solver/geometry/shape_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace asperity::geometry {

double max_asperity_height(const SurfaceMesh& mesh, const MassProperties& props) {
  const Vec3 inv_a2 =
      props.ellipsoid_semi_axes.cwiseProduct(props.ellipsoid_semi_axes).cwiseInverse();
  double h_max = -std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < mesh.vertices.cols(); ++i) {
    const Vec3 q = props.principal_axes.transpose() * (mesh.vertices.col(i) - props.centroid);
    const double r = q.norm();
    if (r == 0) continue;  // the centroid itself is no surface point of a star-shaped particle
    const Vec3 u = q / r;
    const double r_e = 1.0 / std::sqrt(u.cwiseProduct(u).dot(inv_a2));
    h_max = std::max(h_max, r - r_e);
  }
  return h_max;
}

double max_asperity_rel(const SurfaceMesh& mesh, const MassProperties& props) {
  return max_asperity_height(mesh, props) / props.equivalent_radius;
}

ShapeChange shape_change(const SurfaceMesh& source, const MassProperties& source_props,
                         const SurfaceMesh& result, const MassProperties& result_props) {
  ShapeChange s;
  s.volume_change_rel = (result_props.volume - source_props.volume) / source_props.volume;
  s.centroid_shift_rel =
      (result_props.centroid - source_props.centroid).norm() / source_props.equivalent_radius;
  s.max_asperity_rel_source = max_asperity_rel(source, source_props);
  s.max_asperity_rel = max_asperity_rel(result, result_props);
  s.max_asperity_change_rel = s.max_asperity_rel - s.max_asperity_rel_source;
  s.elongation_change = result_props.elongation - source_props.elongation;
  s.flatness_change = result_props.flatness - source_props.flatness;
  return s;
}

}  // namespace asperity::geometry
