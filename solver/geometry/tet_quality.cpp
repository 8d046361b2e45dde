// Tetrahedral mesh quality (issue 3: tet count, minimum dihedral angle, smallest edge, volume).
#include "solver/geometry/tet_quality.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "solver/core/vec.hpp"

namespace asperity::geometry {

TetQuality tet_quality(const TetMesh& mesh) {
  static constexpr int kEdge[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2},
                                      {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
  TetQuality q;
  q.tets = static_cast<long>(mesh.tets.cols());
  q.nodes = static_cast<long>(mesh.nodes.cols());
  std::vector<bool> on_surface(static_cast<std::size_t>(mesh.nodes.cols()), false);
  for (Eigen::Index i = 0; i < mesh.surface.size(); ++i) on_surface[mesh.surface.data()[i]] = true;
  q.interior_nodes = static_cast<long>(std::count(on_surface.begin(), on_surface.end(), false));
  double min_angle = std::numeric_limits<double>::infinity(), max_angle = 0;
  double min_edge = std::numeric_limits<double>::infinity(), max_edge = 0, max_ratio = 0;
  double min_volume = std::numeric_limits<double>::infinity();
  for (Eigen::Index t = 0; t < mesh.tets.cols(); ++t) {
    Vec3 p[4];
    for (int k = 0; k < 4; ++k) p[k] = mesh.nodes.col(mesh.tets(k, t));
    const double v = (p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]) / 6.0;
    q.volume_sum += v;
    min_volume = std::min(min_volume, v);
    // Circumcentre c − p0 = (|a|² b×c' + |b|² c'×a + |c'|² a×b) / (2 a·(b×c')), edges from p0.
    const Vec3 a = p[1] - p[0], b = p[2] - p[0], c = p[3] - p[0];
    const double radius =
        (a.squaredNorm() * b.cross(c) + b.squaredNorm() * c.cross(a) + c.squaredNorm() * a.cross(b))
            .norm() /
        (12.0 * std::abs(v));
    double shortest = std::numeric_limits<double>::infinity();
    for (const auto& e : kEdge) {
      const Vec3 axis = p[e[1]] - p[e[0]];
      shortest = std::min(shortest, axis.norm());
      max_edge = std::max(max_edge, axis.norm());
      min_edge = std::min(min_edge, axis.norm());
      const Vec3 n = axis.normalized();
      Vec3 u = p[e[2]] - p[e[0]], w = p[e[3]] - p[e[0]];
      u -= n * n.dot(u);
      w -= n * n.dot(w);
      const double angle = std::atan2(u.cross(w).norm(), u.dot(w)) * 180.0 / std::numbers::pi;
      min_angle = std::min(min_angle, angle);
      max_angle = std::max(max_angle, angle);
    }
    max_ratio = std::max(max_ratio, radius / shortest);
  }
  if (q.tets > 0) {
    q.min_dihedral_deg = min_angle;
    q.max_dihedral_deg = max_angle;
    q.smallest_edge = min_edge;
    q.longest_edge = max_edge;
    q.max_radius_edge_ratio = max_ratio;
    q.min_volume = min_volume;
  }
  return q;
}

}  // namespace asperity::geometry
