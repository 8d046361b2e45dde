// The cell-grid neighbour list equals the brute-force O(N²) pair list.
#include <random>

#include <gtest/gtest.h>

#include "solver/dem/cell_grid.hpp"

using namespace asperity;

TEST(CellGrid, FindsExactlyTheBruteForcePairs) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> pos(0, 0.2), rad(0.002, 0.006);
  const int n = 600;
  Eigen::Matrix3Xd x(3, n);
  std::vector<double> r(n);
  std::vector<std::uint8_t> fixed(n, 0);
  for (int i = 0; i < n; ++i) {
    x.col(i) = Vec3(pos(rng), pos(rng), 0.25 * pos(rng));
    r[i] = rad(rng);
    fixed[i] = i % 50 == 0;
  }
  const double skin = 0.001;
  const auto pairs = dem::neighbour_pairs(x, r, fixed, skin);
  std::size_t k = 0, expected = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (fixed[i] && fixed[j]) continue;
      if ((x.col(i) - x.col(j)).norm() >= r[i] + r[j] + skin) continue;
      ++expected;
      ASSERT_LT(k, pairs.size());
      EXPECT_EQ(pairs[k].i, i);
      EXPECT_EQ(pairs[k].j, j);
      ++k;
    }
  }
  EXPECT_EQ(pairs.size(), expected);
  EXPECT_GT(expected, 100u);  // the sample is dense enough to mean something
}
