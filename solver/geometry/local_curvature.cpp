// The principal radii at a surface's lowest vertex (local_curvature.hpp).
#include "solver/geometry/local_curvature.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>

namespace asperity::geometry {

double LocalCurvature::equivalent_radius() const {
  if (curvature_min > 0) return 1.0 / std::sqrt(curvature_min * curvature_max);
  if (curvature_max > 0) return 1.0 / curvature_max;
  return 0;
}

double mean_edge_length(const SurfaceMesh& surface) {
  double sum = 0;
  const Eigen::Index n = surface.faces.cols();
  for (Eigen::Index f = 0; f < n; ++f) {
    for (int k = 0; k < 3; ++k) {
      sum += (surface.vertices.col(surface.faces(k, f)) -
              surface.vertices.col(surface.faces((k + 1) % 3, f)))
                 .norm();
    }
  }
  return n > 0 ? sum / static_cast<double>(3 * n) : 0.0;  // each edge counted twice: same mean
}

LocalCurvature lowest_point_curvature(const SurfaceMesh& surface, double patch_radius) {
  LocalCurvature out;
  const Eigen::Index nv = surface.vertices.cols();
  if (nv == 0) return out;
  Eigen::Index low = 0;
  surface.vertices.row(2).minCoeff(&low);
  out.point = surface.vertices.col(low);
  double rho = patch_radius;
  std::vector<Eigen::Index> patch;
  for (int grow = 0; grow < 40; ++grow, rho *= 1.5) {
    patch.clear();
    for (Eigen::Index i = 0; i < nv; ++i) {
      if ((surface.vertices.col(i) - out.point).norm() <= rho) patch.push_back(i);
    }
    if (patch.size() >= 10 || static_cast<Eigen::Index>(patch.size()) == nv) break;
  }
  out.samples = static_cast<int>(patch.size());
  out.patch_radius = rho;
  if (patch.size() < 6) return out;
  // Least squares in coordinates scaled by ρ (a well-conditioned system whatever the size).
  Eigen::MatrixXd a(static_cast<Eigen::Index>(patch.size()), 6);
  Eigen::VectorXd w(static_cast<Eigen::Index>(patch.size()));
  for (std::size_t k = 0; k < patch.size(); ++k) {
    const Vec3 d = (surface.vertices.col(patch[k]) - out.point) / rho;
    const auto r = static_cast<Eigen::Index>(k);
    a.row(r) << 1, d.x(), d.y(), d.x() * d.x(), d.x() * d.y(), d.y() * d.y();
    w(r) = d.z();
  }
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(w);
  // Back to metres: w = ρ ŵ(x/ρ, y/ρ), so the slope is unchanged and the Hessian is H / ρ.
  const Eigen::Vector2d g(c(1), c(2));
  Eigen::Matrix2d h;
  h << 2 * c(3), c(4), c(4), 2 * c(5);
  h /= rho;
  const Eigen::Matrix2d shape = (Eigen::Matrix2d::Identity() + g * g.transpose()).inverse() * h /
                                std::sqrt(1 + g.squaredNorm());
  // Real eigenvalues (shape is similar to a symmetric matrix).
  const double tr = shape.trace(), det = shape.determinant();
  const double disc = std::sqrt(std::max(0.0, 0.25 * tr * tr - det));
  // A curvature whose bending over the patch is round-off (κρ < 1e-9) is none: a flat face.
  const auto settle = [rho](double k) { return std::abs(k) * rho < 1e-9 ? 0.0 : k; };
  out.curvature_min = settle(0.5 * tr - disc);
  out.curvature_max = settle(0.5 * tr + disc);
  const double inf = std::numeric_limits<double>::infinity();
  out.radius_min = out.curvature_max > 0 ? 1.0 / out.curvature_max : inf;
  out.radius_max = out.curvature_min > 0 ? 1.0 / out.curvature_min : inf;
  return out;
}

}  // namespace asperity::geometry
