// Uniform-grid neighbour search (counting sort into cells, then the 27 neighbouring cells).
#include "solver/dem/cell_grid.hpp"

#include <algorithm>
#include <cmath>

namespace asperity::dem {

std::vector<PairContact> neighbour_pairs(const Eigen::Matrix3Xd& x,
                                         const std::vector<double>& radius,
                                         const std::vector<std::uint8_t>& fixed, double skin) {
  const int n = static_cast<int>(radius.size());
  std::vector<PairContact> pairs;
  if (n < 2) return pairs;
  const double r_max = *std::max_element(radius.begin(), radius.end());
  const Eigen::Vector3d lo = x.rowwise().minCoeff(), hi = x.rowwise().maxCoeff();
  double cell = 2 * r_max + skin;
  // Cap the grid at a few cells per sphere so a sparse scene cannot allocate without bound.
  auto dims_for = [&](double c) {
    Eigen::Array3i d;
    for (int k = 0; k < 3; ++k) d[k] = static_cast<int>(std::floor((hi[k] - lo[k]) / c)) + 1;
    return d;
  };
  Eigen::Array3i dims = dims_for(cell);
  while (static_cast<double>(dims.cast<double>().prod()) > 8.0 * n + 1024) {
    cell *= 1.5;
    dims = dims_for(cell);
  }
  auto cell_of = [&](int i) {
    Eigen::Array3i c;
    for (int k = 0; k < 3; ++k) {
      c[k] = std::min(dims[k] - 1, static_cast<int>((x(k, i) - lo[k]) / cell));
    }
    return c;
  };
  auto flat = [&](const Eigen::Array3i& c) {
    return (static_cast<long>(c[2]) * dims[1] + c[1]) * dims[0] + c[0];
  };
  const long n_cells = static_cast<long>(dims[0]) * dims[1] * dims[2];
  std::vector<int> start(n_cells + 1, 0), order(n);
  std::vector<long> cell_index(n);
  for (int i = 0; i < n; ++i) ++start[(cell_index[i] = flat(cell_of(i))) + 1];
  for (long c = 0; c < n_cells; ++c) start[c + 1] += start[c];
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int i = 0; i < n; ++i) order[fill[cell_index[i]]++] = i;
  }
  for (int i = 0; i < n; ++i) {
    const Eigen::Array3i ci = cell_of(i);
    for (int dz = -1; dz <= 1; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const Eigen::Array3i cj = ci + Eigen::Array3i(dx, dy, dz);
          if ((cj < 0).any() || (cj >= dims).any()) continue;
          const long f = flat(cj);
          for (int s = start[f]; s < start[f + 1]; ++s) {
            const int j = order[s];
            if (j <= i || (fixed[i] && fixed[j])) continue;
            const double reach = radius[i] + radius[j] + skin;
            if ((x.col(i) - x.col(j)).squaredNorm() < reach * reach)
              pairs.push_back({.i = i, .j = j});
          }
        }
      }
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const PairContact& a, const PairContact& b) {
    return a.i != b.i ? a.i < b.i : a.j < b.j;
  });
  return pairs;
}

}  // namespace asperity::dem
