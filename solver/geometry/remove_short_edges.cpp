// Short-edge collapse after simplification (geometry/remove_short_edges.hpp: what and why).
#include "solver/geometry/remove_short_edges.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <utility>
#include <vector>

#include "solver/core/vec.hpp"

namespace asperity::geometry {
namespace {

using Face = std::array<int, 3>;

// Surface as growable lists while it is edited.
struct Soup {
  std::vector<Vec3> x;
  std::vector<Face> f;
};

// Signed volume × 6 of the solid a closed outward surface bounds, summed about `origin`.
double six_volume(const Soup& s, const Vec3& origin) {
  double v = 0;
  for (const Face& t : s.f)
    v += (s.x[t[0]] - origin).cross(s.x[t[1]] - origin).dot(s.x[t[2]] - origin);
  return v;
}

struct EdgeRatio {
  int a = -1, b = -1;
  double length = 0, ratio = 0;
};

// Every edge with its length over the mean length of the other edges at its two vertices. Each
// edge appears in two faces, so summing over face sides counts every edge twice at each vertex,
// which leaves the means unchanged.
std::vector<EdgeRatio> edge_ratios(const Soup& s) {
  std::vector<double> sum(s.x.size(), 0.0);
  std::vector<int> count(s.x.size(), 0);
  std::vector<EdgeRatio> edges;
  for (const Face& t : s.f) {
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      const double l = (s.x[a] - s.x[b]).norm();
      sum[a] += l, sum[b] += l, ++count[a], ++count[b];
      if (a < b) edges.push_back({.a = a, .b = b, .length = l});
    }
  }
  for (EdgeRatio& e : edges) {
    const int n = count[e.a] + count[e.b] - 4;
    const double others = (sum[e.a] + sum[e.b] - 4 * e.length) / std::max(n, 1);
    e.ratio = others > 0 ? e.length / others : std::numeric_limits<double>::infinity();
  }
  return edges;
}

// Collapses edge (a, b) to one vertex when the checks of the header pass; b's index stays unused
// (removed by the caller). Returns whether it did.
bool collapse(Soup& s, int a, int b) {
  std::vector<int> ring;  // faces with a or b
  std::vector<int> shared;
  std::set<int> around_a, around_b;
  for (int i = 0; i < static_cast<int>(s.f.size()); ++i) {
    const Face& t = s.f[i];
    const bool has_a = t[0] == a || t[1] == a || t[2] == a;
    const bool has_b = t[0] == b || t[1] == b || t[2] == b;
    if (!has_a && !has_b) continue;
    ring.push_back(i);
    if (has_a && has_b) shared.push_back(i);
    for (const int v : t) {
      if (has_a && v != a) around_a.insert(v);
      if (has_b && v != b) around_b.insert(v);
    }
  }
  // Link condition (closed triangle 2-manifold): a and b share exactly the two opposite vertices.
  std::vector<int> common;
  std::set_intersection(around_a.begin(), around_a.end(), around_b.begin(), around_b.end(),
                        std::back_inserter(common));
  if (shared.size() != 2 || common.size() != 2 || s.x.size() <= 4) return false;
  // The volume is linear in the new vertex p: 6V = Σ over the remaining ring faces of
  // p·(q₁ × q₂) (q₁, q₂ the face's other vertices in its order) + the rest, all about the
  // midpoint m. Keeping it is the plane p·G = 6 V_ring; p is the midpoint projected onto it.
  const Vec3 m = 0.5 * (s.x[a] + s.x[b]);
  double six_v_ring = 0;
  Vec3 g = Vec3::Zero();
  for (const int i : ring) {
    const Face& t = s.f[i];
    six_v_ring += (s.x[t[0]] - m).cross(s.x[t[1]] - m).dot(s.x[t[2]] - m);
    if (std::find(shared.begin(), shared.end(), i) != shared.end()) continue;
    for (int k = 0; k < 3; ++k) {
      if (t[k] == a || t[k] == b) g += (s.x[t[(k + 1) % 3]] - m).cross(s.x[t[(k + 2) % 3]] - m);
    }
  }
  const double length = (s.x[a] - s.x[b]).norm();
  if (g.squaredNorm() <= 0) return false;
  const Vec3 p = m + (six_v_ring / g.squaredNorm()) * g;
  if ((p - m).norm() >= length) return false;
  // No remaining face turned over, none degenerate, no new edge shorter than the one removed.
  std::vector<std::pair<int, Face>> changed;
  for (const int i : ring) {
    if (std::find(shared.begin(), shared.end(), i) != shared.end()) continue;
    Face t = s.f[i];
    const Vec3 n0 = (s.x[t[1]] - s.x[t[0]]).cross(s.x[t[2]] - s.x[t[0]]);
    std::array<Vec3, 3> q{s.x[t[0]], s.x[t[1]], s.x[t[2]]};
    for (int k = 0; k < 3; ++k) {
      if (t[k] == a || t[k] == b) {
        t[k] = a;
        q[k] = p;
        if ((q[(k + 1) % 3] - p).norm() <= length || (q[(k + 2) % 3] - p).norm() <= length)
          return false;
      }
    }
    const Vec3 n1 = (q[1] - q[0]).cross(q[2] - q[0]);
    if (n1.dot(n0) <= 0 || n1.norm() <= 0) return false;
    changed.push_back({i, t});
  }
  for (const auto& [i, t] : changed) s.f[i] = t;
  s.x[a] = p;
  std::sort(shared.begin(), shared.end());
  s.f.erase(s.f.begin() + shared[1]);
  s.f.erase(s.f.begin() + shared[0]);
  return true;
}

// Removes vertex b (no face uses it): the higher indices move down by one.
void drop_vertex(Soup& s, int b) {
  s.x.erase(s.x.begin() + b);
  for (Face& t : s.f)
    for (int& v : t)
      if (v > b) --v;
}

// Bisects the longest edge at its midpoint: faces (u, v, w) and (v, u, x) become (u, m, w),
// (m, v, w), (v, m, x), (m, u, x), two triangles more, each in its parent's plane.
void bisect_longest_edge(Soup& s) {
  int u = -1, v = -1;
  double longest = -1;
  for (const Face& t : s.f) {
    for (int k = 0; k < 3; ++k) {
      const double l = (s.x[t[k]] - s.x[t[(k + 1) % 3]]).norm();
      if (l > longest) longest = l, u = t[k], v = t[(k + 1) % 3];
    }
  }
  const int m = static_cast<int>(s.x.size());
  s.x.push_back(0.5 * (s.x[u] + s.x[v]));
  const std::size_t n = s.f.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      const int p = s.f[i][k], q = s.f[i][(k + 1) % 3], w = s.f[i][(k + 2) % 3];
      if ((p == u && q == v) || (p == v && q == u)) {
        s.f[i] = {p, m, w};
        s.f.push_back({m, q, w});
        break;
      }
    }
  }
}

}  // namespace

ShortEdgeRepair remove_short_edges(SurfaceMesh& mesh, const ShortEdgeOptions& options) {
  ShortEdgeRepair out;
  Soup s;
  for (Eigen::Index i = 0; i < mesh.vertices.cols(); ++i) s.x.push_back(mesh.vertices.col(i));
  for (Eigen::Index i = 0; i < mesh.faces.cols(); ++i)
    s.f.push_back({mesh.faces(0, i), mesh.faces(1, i), mesh.faces(2, i)});
  for (const EdgeRatio& e : edge_ratios(s)) out.short_edges += e.ratio < options.ratio;
  if (out.short_edges == 0) return out;
  const Vec3 origin = s.x[0];
  const double six_v0 = six_volume(s, origin);
  // Shortest relative to its ring first; an edge that fails a check is not tried again.
  std::vector<std::array<Vec3, 2>> tried;
  for (int round = 0; round < options.max_collapses; ++round) {
    std::vector<EdgeRatio> edges = edge_ratios(s);
    std::sort(edges.begin(), edges.end(), [](const EdgeRatio& x, const EdgeRatio& y) {
      return x.ratio < y.ratio || (x.ratio == y.ratio && std::pair(x.a, x.b) < std::pair(y.a, y.b));
    });
    bool done = false;
    for (const EdgeRatio& e : edges) {
      if (e.ratio >= options.ratio) break;
      const std::array<Vec3, 2> ends{s.x[e.a], s.x[e.b]};
      if (std::any_of(tried.begin(), tried.end(), [&](const std::array<Vec3, 2>& t) {
            return t[0] == ends[0] && t[1] == ends[1];
          })) {
        continue;
      }
      tried.push_back(ends);
      if (collapse(s, e.a, e.b)) {
        drop_vertex(s, e.b);
        bisect_longest_edge(s);
        ++out.collapsed;
        done = true;
        break;
      }
    }
    if (!done) break;
  }
  out.volume_change_rel = std::abs(six_volume(s, origin) - six_v0) / std::abs(six_v0);
  mesh.vertices.resize(3, static_cast<Eigen::Index>(s.x.size()));
  for (std::size_t i = 0; i < s.x.size(); ++i)
    mesh.vertices.col(static_cast<Eigen::Index>(i)) = s.x[i];
  mesh.faces.resize(3, static_cast<Eigen::Index>(s.f.size()));
  for (std::size_t i = 0; i < s.f.size(); ++i)
    for (int k = 0; k < 3; ++k) mesh.faces(k, static_cast<Eigen::Index>(i)) = s.f[i][k];
  return out;
}

}  // namespace asperity::geometry
