// Node numbering along a Morton curve (morton_node_order.hpp).
#include "solver/geometry/morton_node_order.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

namespace asperity::geometry {
namespace {

constexpr int kBits = 21;  // per axis: three of them fill a 64-bit code

// The kBits low bits of v, moved to every third bit (bit i to bit 3i).
std::uint64_t spread_bits(std::uint64_t v) {
  v &= (std::uint64_t{1} << kBits) - 1;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

}  // namespace

std::vector<int> morton_node_order(const Eigen::Matrix3Xd& nodes) {
  const auto n = static_cast<std::size_t>(nodes.cols());
  std::vector<int> new_index(n);
  if (n == 0) return new_index;
  const Vec3 lo = nodes.rowwise().minCoeff(), hi = nodes.rowwise().maxCoeff();
  const double span = (hi - lo).maxCoeff();
  const double cells = static_cast<double>((std::uint64_t{1} << kBits) - 1);
  const double scale = span > 0 ? cells / span : 0.0;
  std::vector<std::uint64_t> code(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t c = 0;
    for (int d = 0; d < 3; ++d) {
      const double q =
          std::clamp((nodes(d, static_cast<Eigen::Index>(i)) - lo[d]) * scale, 0.0, cells);
      c |= spread_bits(static_cast<std::uint64_t>(q)) << d;
    }
    code[i] = c;
  }
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return code[static_cast<std::size_t>(a)] < code[static_cast<std::size_t>(b)];
  });
  for (std::size_t i = 0; i < n; ++i)
    new_index[static_cast<std::size_t>(order[i])] = static_cast<int>(i);
  return new_index;
}

void number_nodes_along_morton_curve(TetMesh& m) {
  const std::vector<int> new_index = morton_node_order(m.nodes);
  Eigen::Matrix3Xd nodes(3, m.nodes.cols());
  for (Eigen::Index i = 0; i < m.nodes.cols(); ++i) {
    nodes.col(new_index[static_cast<std::size_t>(i)]) = m.nodes.col(i);
  }
  m.nodes = std::move(nodes);
  for (Eigen::Index k = 0; k < m.tets.size(); ++k) m.tets.data()[k] = new_index[m.tets.data()[k]];
  for (Eigen::Index k = 0; k < m.surface.size(); ++k) {
    m.surface.data()[k] = new_index[m.surface.data()[k]];
  }
}

}  // namespace asperity::geometry
