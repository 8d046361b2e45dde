// Sort-and-sweep broad phase over the surface tetrahedra.
#include "fdem/broad_phase.hpp"

#include <algorithm>
#include <numeric>

namespace asperity::fdem {

std::vector<TetPair> candidate_pairs(const Eigen::Matrix3Xd& x, const Eigen::Matrix4Xi& tets,
                                     const std::vector<int>& tet_body,
                                     const std::vector<std::uint8_t>& body_fixed, double margin) {
  const int n = static_cast<int>(tets.cols());
  Eigen::Matrix3Xd lo(3, n), hi(3, n);
  for (int k = 0; k < n; ++k) {
    Vec3 a = x.col(tets(0, k)), b = a;
    for (int i = 1; i < 4; ++i) {
      a = a.cwiseMin(x.col(tets(i, k)));
      b = b.cwiseMax(x.col(tets(i, k)));
    }
    lo.col(k) = a.array() - 0.5 * margin;
    hi.col(k) = b.array() + 0.5 * margin;
  }
  std::vector<TetPair> out;
  if (n == 0) return out;
  // Sweep along the axis where the box centres spread most: fewest false interval overlaps.
  const Eigen::Matrix3Xd mid = 0.5 * (lo + hi);
  const Vec3 spread = mid.rowwise().maxCoeff() - mid.rowwise().minCoeff();
  Eigen::Index axis;
  spread.maxCoeff(&axis);
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return lo(axis, a) < lo(axis, b); });
  for (int s = 0; s < n; ++s) {
    const int i = order[s];
    for (int t = s + 1; t < n; ++t) {
      const int j = order[t];
      if (lo(axis, j) > hi(axis, i)) break;
      if (tet_body[i] == tet_body[j]) continue;
      if (body_fixed[tet_body[i]] && body_fixed[tet_body[j]]) continue;
      if ((lo.col(i).array() > hi.col(j).array()).any() ||
          (lo.col(j).array() > hi.col(i).array()).any()) {
        continue;
      }
      out.push_back({.a = std::min(i, j), .b = std::max(i, j)});
    }
  }
  std::sort(out.begin(), out.end(), [](const TetPair& p, const TetPair& q) {
    return p.a < q.a || (p.a == q.a && p.b < q.b);
  });
  return out;
}

}  // namespace asperity::fdem
