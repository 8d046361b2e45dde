// The cell-grid neighbour list equals the brute-force O(N²) pair list; the scene's starting-overlap
// check, which runs on it, finds what the test of every pair found.
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "scenes/dem_scenes.hpp"
#include "solver/core/error.hpp"
#include "solver/dem/cell_grid.hpp"
#include "solver/run/run_scene.hpp"

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

// A 10 × 10 × 10 lattice of spheres 1e-9 r apart (none overlapping: the run starts) with two
// pairs pushed into each other by 1e-12 of a radius, far apart in index order: the scene is
// refused naming the pair whose first sphere comes first (what the test of every pair named),
// and two fixed spheres that overlap are refused too (the check includes fixed pairs, which the
// neighbour list of the step leaves out).
TEST(CellGrid, StartingOverlapIsFoundAsByTheTestOfEveryPair) {
  const double r = 0.001, spacing = 2 * r * (1 + 1e-9);
  auto lattice = [&] {
    scene::SceneDef s;
    s.name = "lattice";
    s.duration = 1e-7;
    s.materials = {test::glass()};
    for (int z = 0; z < 10; ++z)
      for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 10; ++x) {
          std::string name = "s";
          name += std::to_string(s.bodies.size());
          s.bodies.push_back({.name = name,
                              .material = 0,
                              .shape = scene::SphereShape{.radius = r},
                              .position = Vec3(x, y, z) * spacing});
        }
    s.record = {.body = 0, .every = 1};
    return s;
  };
  scene::SceneDef s = lattice();
  EXPECT_NO_THROW(run::run_scene(s, {.keep_rows = false}));
  // s700 and s710 (neighbours in y), s30 and s31 (neighbours in x): s30's pair is named.
  s.bodies[710].position.y() -= 2e-12 * r + 2e-9 * r;
  s.bodies[31].position.x() -= 2e-12 * r + 2e-9 * r;
  try {
    run::run_scene(s);
    ADD_FAILURE() << "the overlapping scene ran";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("\"s30\": position: starts overlapping \"s31\""), std::string::npos)
        << what;
  }
  s = lattice();
  s.bodies[500].fixed = s.bodies[501].fixed = true;
  s.bodies[501].position.x() -= 2e-12 * r + 2e-9 * r;
  EXPECT_THROW(run::run_scene(s), InputError);
}
