// Broad phase: the sort-and-sweep list equals the brute-force list, for three bodies and twelve.
#include <gtest/gtest.h>

#include <random>

#include "solver/fdem/broad_phase.hpp"
#include "solver/fdem/structured_mesh.hpp"

namespace asperity::fdem {
namespace {

// Every pair of different bodies, not both fixed, whose grown boxes meet, by testing all pairs.
std::vector<std::pair<int, int>> brute_force(const Eigen::Matrix3Xd& x,
                                             const Eigen::Matrix4Xi& tets,
                                             const std::vector<int>& body,
                                             const std::vector<std::uint8_t>& fixed,
                                             double margin) {
  std::vector<std::pair<int, int>> brute;
  auto box = [&](int k, Vec3& lo, Vec3& hi) {
    lo = hi = x.col(tets(0, k));
    for (int i = 1; i < 4; ++i)
      lo = lo.cwiseMin(x.col(tets(i, k))), hi = hi.cwiseMax(x.col(tets(i, k)));
    lo.array() -= 0.5 * margin;
    hi.array() += 0.5 * margin;
  };
  for (int i = 0; i < tets.cols(); ++i) {
    for (int j = i + 1; j < tets.cols(); ++j) {
      if (body[i] == body[j] || (fixed[body[i]] && fixed[body[j]])) continue;
      Vec3 li, hi, lj, hj;
      box(i, li, hi);
      box(j, lj, hj);
      if ((li.array() <= hj.array()).all() && (lj.array() <= hi.array()).all())
        brute.emplace_back(i, j);
    }
  }
  return brute;
}

// The bodies' meshes as one world: nodes and tetrahedra concatenated, each tetrahedron's body.
struct Bodies {
  Eigen::Matrix3Xd x;
  Eigen::Matrix4Xi tets;
  std::vector<int> body;
};

Bodies assemble(const std::vector<TetMesh>& meshes) {
  Eigen::Index nn = 0, nt = 0;
  for (const TetMesh& m : meshes) nn += m.nodes.cols(), nt += m.tets.cols();
  Bodies w{Eigen::Matrix3Xd(3, nn), Eigen::Matrix4Xi(4, nt), {}};
  Eigen::Index node = 0, tet = 0;
  for (std::size_t b = 0; b < meshes.size(); ++b) {
    const TetMesh& m = meshes[b];
    w.x.middleCols(node, m.nodes.cols()) = m.nodes;
    w.tets.middleCols(tet, m.tets.cols()) = (m.tets.array() + static_cast<int>(node)).matrix();
    for (Eigen::Index k = 0; k < m.tets.cols(); ++k) w.body.push_back(static_cast<int>(b));
    node += m.nodes.cols(), tet += m.tets.cols();
  }
  return w;
}

// The sort-and-sweep list equals the brute-force one, pair by pair and in the same order; at
// least `least` pairs, so that the comparison is not between two empty lists.
void expect_matches_brute_force(const Bodies& w, const std::vector<std::uint8_t>& fixed,
                                std::size_t least) {
  const double margin = 0.05;
  const auto pairs = candidate_pairs(w.x, w.tets, w.body, fixed, margin);
  const auto brute = brute_force(w.x, w.tets, w.body, fixed, margin);
  ASSERT_GT(brute.size(), least);
  ASSERT_EQ(pairs.size(), brute.size());
  for (std::size_t k = 0; k < brute.size(); ++k) {
    EXPECT_EQ(pairs[k].a, brute[k].first);
    EXPECT_EQ(pairs[k].b, brute[k].second);
  }
}

TEST(BroadPhase, MatchesBruteForce) {
  // Two balls touching plus a fixed block under them, randomly perturbed.
  TetMesh b = ball_mesh(1.0, 3);
  b.nodes.colwise() += Vec3(1.9, 0.2, 0.1);
  Bodies w =
      assemble({ball_mesh(1.0, 3), b, box_mesh(Vec3(-3, -3, -2), Vec3(3, 3, -0.9), 2, 2, 1)});
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  for (Eigen::Index i = 0; i < w.x.size(); ++i) w.x.data()[i] += u(rng);
  expect_matches_brute_force(w, {0, 0, 1}, 10u);
}

// Twelve bodies: ten balls scattered so that some touch (in every direction, so the bodies'
// sweep along x meets pairs that overlap in x but not in y or z) and two fixed blocks that touch
// each other (their pairs are never candidates).
TEST(BroadPhase, ManyBodiesMatchBruteForce) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> pos(-2.5, 2.5), jitter(-0.02, 0.02);
  std::vector<TetMesh> meshes;
  std::vector<std::uint8_t> fixed;
  for (int k = 0; k < 10; ++k) {
    TetMesh m = ball_mesh(0.6, 2);
    m.nodes.colwise() += Vec3(pos(rng), pos(rng), 0.3 * pos(rng));
    meshes.push_back(m);
    fixed.push_back(0);
  }
  meshes.push_back(box_mesh(Vec3(-3, -3, -2), Vec3(0, 3, -0.9), 2, 2, 1));
  meshes.push_back(box_mesh(Vec3(0, -3, -2), Vec3(3, 3, -0.9), 2, 2, 1));
  fixed.push_back(1);
  fixed.push_back(1);
  Bodies w = assemble(meshes);
  for (Eigen::Index i = 0; i < w.x.size(); ++i) w.x.data()[i] += jitter(rng);
  expect_matches_brute_force(w, fixed, 100u);
}

}  // namespace
}  // namespace asperity::fdem
