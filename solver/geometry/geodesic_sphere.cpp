// Geodesic icosphere (used by random_particle and by the convergence tests).
#include "solver/geometry/geodesic_sphere.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

#include "solver/core/error.hpp"
#include "solver/core/vec.hpp"

namespace asperity::geometry {
namespace {

// The regular icosahedron: the 12 points (0, ±1, ±φ) cyclically; its faces are the triples at
// mutual distance 2 (the edge length), oriented outward.
void icosahedron(std::vector<Vec3>& v, std::vector<std::array<int, 3>>& f) {
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  for (double s1 : {-1.0, 1.0})
    for (double s2 : {-1.0, 1.0}) {
      v.emplace_back(0, s1, s2 * phi);
      v.emplace_back(s1, s2 * phi, 0);
      v.emplace_back(s2 * phi, 0, s1);
    }
  auto edge = [&](int a, int b) { return std::abs((v[a] - v[b]).norm() - 2.0) < 1e-9; };
  for (int a = 0; a < 12; ++a)
    for (int b = a + 1; b < 12; ++b)
      for (int c = b + 1; c < 12; ++c)
        if (edge(a, b) && edge(b, c) && edge(a, c)) {
          if (v[a].dot((v[b] - v[a]).cross(v[c] - v[a])) > 0) {
            f.push_back({a, b, c});
          } else {
            f.push_back({a, c, b});
          }
        }
  ASPERITY_CHECK(f.size() == 20);
}

// A grid point is keyed by its integer barycentric weights on the icosahedron's corners, so points
// on shared edges are one vertex and computed identically from either face.
}  // namespace

SurfaceMesh geodesic_sphere(int n) {
  ASPERITY_CHECK(n >= 1);
  std::vector<Vec3> u;
  std::vector<std::array<int, 3>> tris;
  std::vector<Vec3> ico;
  std::vector<std::array<int, 3>> ico_faces;
  icosahedron(ico, ico_faces);
  std::map<std::array<int, 6>, int> index;
  auto vertex = [&](const std::array<int, 3>& corner, int wa, int wb, int wc) {
    std::array<std::pair<int, int>, 3> w{
        {{wa ? corner[0] : -1, wa}, {wb ? corner[1] : -1, wb}, {wc ? corner[2] : -1, wc}}};
    std::sort(w.begin(), w.end());  // the same order, hence the same sum, from every face
    std::array<int, 6> key{};
    for (int k = 0; k < 3; ++k) {
      key[2 * k] = w[k].first;
      key[2 * k + 1] = w[k].second;
    }
    auto [it, fresh] = index.emplace(key, static_cast<int>(u.size()));
    if (fresh) {
      Vec3 x = Vec3::Zero();
      for (const auto& [c, wt] : w)
        if (wt > 0) x += static_cast<double>(wt) * ico[c];
      u.push_back(x.normalized());
    }
    return it->second;
  };
  for (const auto& f : ico_faces) {
    std::vector<std::vector<int>> grid(n + 1);
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) grid[i].push_back(vertex(f, n - i - j, i, j));
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        tris.push_back({grid[i][j], grid[i + 1][j], grid[i][j + 1]});
        if (i + j < n - 1) tris.push_back({grid[i + 1][j], grid[i + 1][j + 1], grid[i][j + 1]});
      }
  }
  SurfaceMesh out;
  out.vertices.resize(3, static_cast<Eigen::Index>(u.size()));
  for (std::size_t i = 0; i < u.size(); ++i) out.vertices.col(static_cast<Eigen::Index>(i)) = u[i];
  out.faces.resize(3, static_cast<Eigen::Index>(tris.size()));
  for (std::size_t i = 0; i < tris.size(); ++i)
    for (int c = 0; c < 3; ++c) out.faces(c, static_cast<Eigen::Index>(i)) = tris[i][c];
  return out;
}

}  // namespace asperity::geometry
