// Element size apart from surface geometry: the size field, in-plane longest-edge bisection of the
// surface, and the tetrahedron-count estimate that guards both.
#include "solver/geometry/element_size.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <queue>
#include <sstream>
#include <unordered_map>
#include <utility>
#include <vector>

#include "solver/core/error.hpp"

namespace asperity::geometry {

double ElementSize::at(const Vec3& x) const {
  if (growth <= 0) return size;
  const double d = std::max(0.0, (x - focus).norm() - focus_radius);
  return std::min(far, size + growth * d);
}

namespace {

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

class Bisection {
 public:
  Bisection(const SurfaceMesh& s, const ElementSize& size, long max_faces)
      : size_(size), max_faces_(max_faces) {
    vertices_.reserve(static_cast<std::size_t>(s.vertices.cols()));
    for (Eigen::Index i = 0; i < s.vertices.cols(); ++i) vertices_.emplace_back(s.vertices.col(i));
    tris_.reserve(static_cast<std::size_t>(s.faces.cols()));
    for (Eigen::Index f = 0; f < s.faces.cols(); ++f) {
      tris_.push_back({s.faces(0, f), s.faces(1, f), s.faces(2, f)});
      for (int k = 0; k < 3; ++k)
        attach(tris_.back()[k], tris_.back()[(k + 1) % 3], static_cast<int>(f));
    }
  }

  SurfaceMesh run() {
    for (const auto& [key, tris] : edges_) offer(key);
    while (!queue_.empty()) {
      const std::uint64_t key = queue_.top().second;
      queue_.pop();
      if (edges_.count(key) != 0 && too_long(key)) refine(key);
    }
    SurfaceMesh out;
    out.vertices.resize(3, static_cast<Eigen::Index>(vertices_.size()));
    for (std::size_t i = 0; i < vertices_.size(); ++i)
      out.vertices.col(static_cast<Eigen::Index>(i)) = vertices_[i];
    out.faces.resize(3, static_cast<Eigen::Index>(tris_.size()));
    for (std::size_t t = 0; t < tris_.size(); ++t)
      out.faces.col(static_cast<Eigen::Index>(t)) << tris_[t][0], tris_[t][1], tris_[t][2];
    return out;
  }

 private:
  static int first(std::uint64_t key) { return static_cast<int>(key >> 32); }
  static int second(std::uint64_t key) { return static_cast<int>(key & 0xffffffffu); }

  void attach(int a, int b, int tri) {
    auto& slot = edges_.try_emplace(edge_key(a, b), std::array<int, 2>{-1, -1}).first->second;
    (slot[0] < 0 ? slot[0] : slot[1]) = tri;
  }
  void replace(int a, int b, int from, int to) {
    auto& slot = edges_.at(edge_key(a, b));
    (slot[0] == from ? slot[0] : slot[1]) = to;
  }
  double length2(std::uint64_t key) const {
    return (vertices_[first(key)] - vertices_[second(key)]).squaredNorm();
  }
  double ratio(std::uint64_t key) const {
    const Vec3 mid = 0.5 * (vertices_[first(key)] + vertices_[second(key)]);
    return std::sqrt(length2(key)) / size_.at(mid);
  }
  bool too_long(std::uint64_t key) const { return ratio(key) > 1.0; }
  void offer(std::uint64_t key) {
    if (too_long(key)) queue_.emplace(ratio(key), key);
  }
  // Longest edge of a triangle; ties broken by the vertex indices so that two triangles agree.
  std::uint64_t longest(int tri) const {
    const auto& t = tris_[tri];
    std::uint64_t best = edge_key(t[0], t[1]);
    for (int k = 1; k < 3; ++k) {
      const std::uint64_t e = edge_key(t[k], t[(k + 1) % 3]);
      const double l = length2(e), lb = length2(best);
      if (l > lb || (l == lb && e > best)) best = e;
    }
    return best;
  }

  // Splits edge `key` once it is the longest edge of both its triangles, splitting the longer
  // edges of the propagation path first.
  void refine(std::uint64_t key) {
    std::vector<std::uint64_t> path{key};
    while (!path.empty()) {
      const std::uint64_t e = path.back();
      const auto it = edges_.find(e);
      if (it == edges_.end()) {  // split meanwhile
        path.pop_back();
        continue;
      }
      bool ready = true;
      for (const int t : it->second) {
        if (t < 0) continue;
        const std::uint64_t l = longest(t);
        if (l != e) {
          path.push_back(l);
          ready = false;
          break;
        }
      }
      if (!ready) continue;
      bisect(e);
      path.pop_back();
    }
  }

  void bisect(std::uint64_t key) {
    const int a = first(key), b = second(key);
    const int m = static_cast<int>(vertices_.size());
    vertices_.push_back(0.5 * (vertices_[a] + vertices_[b]));
    const std::array<int, 2> tris = edges_.at(key);
    edges_.erase(key);
    for (const int t : tris) {
      if (t < 0) continue;
      // Rotate so that the split edge is (p, q) in the triangle's own orientation.
      std::array<int, 3> v = tris_[t];
      while (!((v[0] == a && v[1] == b) || (v[0] == b && v[1] == a)))
        std::rotate(v.begin(), v.begin() + 1, v.end());
      const int p = v[0], q = v[1], r = v[2];
      const int t2 = static_cast<int>(tris_.size());
      if (static_cast<long>(tris_.size()) >= max_faces_) {
        throw InputError("subdividing the surface for the element size would pass " +
                         std::to_string(max_faces_) + " triangles");
      }
      tris_[t] = {p, m, r};
      tris_.push_back({m, q, r});
      replace(q, r, t, t2);
      attach(p, m, t);
      attach(m, q, t2);
      attach(m, r, t);
      attach(m, r, t2);
    }
    for (const int n : {a, b}) offer(edge_key(n, m));
    for (const int t : tris)
      if (t >= 0)
        for (const int x : tris_[t])
          if (x != m) offer(edge_key(m, x));
  }

  ElementSize size_;
  long max_faces_;
  std::vector<Vec3> vertices_;
  std::vector<std::array<int, 3>> tris_;
  std::unordered_map<std::uint64_t, std::array<int, 2>> edges_;
  std::priority_queue<std::pair<double, std::uint64_t>> queue_;
};

}  // namespace

SurfaceMesh subdivide_surface(const SurfaceMesh& surface, const ElementSize& size, long max_faces) {
  ASPERITY_CHECK(size.set());
  return Bisection(surface, size, max_faces).run();
}

double estimated_tets(const SurfaceMesh& surface, const ElementSize& size) {
  // Cones from the vertex mean o over each face: a point o + s (c_f − o), s in [0, 1], sweeps
  // the cone with volume density 3 s² ds; the size is sampled along that ray (16 midpoints).
  const Vec3 o = surface.vertices.rowwise().mean();
  constexpr int kSamples = 16;
  constexpr double kRegular = 0.11785113019775793;  // 1/(6√2): regular tetrahedron volume / h³
  constexpr double kQualityPacking = 1.5;
  double count = 0;
  for (Eigen::Index f = 0; f < surface.faces.cols(); ++f) {
    const Vec3 a = surface.vertices.col(surface.faces(0, f)),
               b = surface.vertices.col(surface.faces(1, f)),
               c = surface.vertices.col(surface.faces(2, f));
    const double cone = (a - o).cross(b - o).dot(c - o) / 6.0;
    const Vec3 centre = (a + b + c) / 3.0;
    for (int k = 0; k < kSamples; ++k) {
      const double s = (k + 0.5) / kSamples;
      const double h = size.at(o + s * (centre - o));
      count += cone * 3 * s * s / kSamples / (kRegular * h * h * h);
    }
  }
  return kQualityPacking * count;
}

std::string element_size_problem(const SurfaceMesh& surface, const ElementSize& size,
                                 double max_tets) {
  std::ostringstream os;
  os.precision(6);
  if (!std::isfinite(size.size) || size.size <= 0) {
    os << size.size << " is not a positive length in metres";
    return os.str();
  }
  const Vec3 extent = surface.vertices.rowwise().maxCoeff() - surface.vertices.rowwise().minCoeff();
  if (size.size > extent.maxCoeff()) {
    os << size.size << " m is larger than the particle (" << extent.maxCoeff() << " m across)";
    return os.str();
  }
  const double tets = estimated_tets(surface, size);
  if (!(tets <= max_tets)) {
    os << size.size << " m would make about " << static_cast<double>(std::llround(tets / 1e5)) / 10
       << " M tetrahedra (limit " << max_tets / 1e6 << " M)";
    return os.str();
  }
  return "";
}

}  // namespace asperity::geometry
