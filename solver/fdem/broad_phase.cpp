// Broad phase: body boxes first, then sort and sweep between the two bodies of each pair.
#include "solver/fdem/broad_phase.hpp"

#include <algorithm>
#include <numeric>

namespace asperity::fdem {
namespace {

struct Boxes {
  Eigen::Matrix3Xd lo, hi;
  bool overlap(int i, int j) const {
    return !((lo.col(i).array() > hi.col(j).array()).any() ||
             (lo.col(j).array() > hi.col(i).array()).any());
  }
};

// The tetrahedra of `body` (its list `own`) whose box meets the box [lo, hi], sorted by their
// lower end along `axis`.
std::vector<int> near_box(const Boxes& b, const std::vector<int>& own, const Vec3& lo,
                          const Vec3& hi, Eigen::Index axis) {
  std::vector<int> out;
  for (int k : own) {
    if ((b.lo.col(k).array() <= hi.array()).all() && (lo.array() <= b.hi.col(k).array()).all()) {
      out.push_back(k);
    }
  }
  std::sort(out.begin(), out.end(), [&](int i, int j) { return b.lo(axis, i) < b.lo(axis, j); });
  return out;
}

// Every overlapping pair with one box from each list (both sorted by lower end along `axis`):
// one merged sweep with an active list per side, so boxes of the same body are never compared.
// Each box enters its side's list once and leaves it once (when a box of the other side starts
// past its end), and every other comparison is an x-interval overlap across the two lists:
// O(n + k) after the sort.
void sweep_two(const Boxes& b, const std::vector<int>& p, const std::vector<int>& q,
               Eigen::Index axis, std::vector<TetPair>& out) {
  std::vector<int> active_p, active_q;
  std::size_t i = 0, j = 0;
  auto visit = [&](int k, std::vector<int>& mine, std::vector<int>& theirs) {
    const double start = b.lo(axis, k);
    std::size_t kept = 0;
    for (int other : theirs) {
      if (b.hi(axis, other) < start) continue;  // ended before k starts: drop it
      theirs[kept++] = other;
      if (b.overlap(k, other)) out.push_back({.a = std::min(k, other), .b = std::max(k, other)});
    }
    theirs.resize(kept);
    mine.push_back(k);
  };
  while (i < p.size() || j < q.size()) {
    if (j == q.size() || (i < p.size() && b.lo(axis, p[i]) <= b.lo(axis, q[j]))) {
      visit(p[i++], active_p, active_q);
    } else {
      visit(q[j++], active_q, active_p);
    }
  }
}

}  // namespace

std::vector<TetPair> candidate_pairs(const Eigen::Matrix3Xd& x, const Eigen::Matrix4Xi& tets,
                                     const std::vector<int>& tet_body,
                                     const std::vector<std::uint8_t>& body_fixed, double margin) {
  const int n = static_cast<int>(tets.cols());
  std::vector<TetPair> out;
  if (n == 0) return out;
  Boxes b{.lo = Eigen::Matrix3Xd(3, n), .hi = Eigen::Matrix3Xd(3, n)};
  const int n_bodies = static_cast<int>(body_fixed.size());
  std::vector<std::vector<int>> own(static_cast<std::size_t>(n_bodies));
  Eigen::Matrix3Xd body_lo = Eigen::Matrix3Xd::Constant(3, n_bodies, 1e300);
  Eigen::Matrix3Xd body_hi = Eigen::Matrix3Xd::Constant(3, n_bodies, -1e300);
  for (int k = 0; k < n; ++k) {
    Vec3 a = x.col(tets(0, k)), c = a;
    for (int i = 1; i < 4; ++i) {
      a = a.cwiseMin(x.col(tets(i, k)));
      c = c.cwiseMax(x.col(tets(i, k)));
    }
    b.lo.col(k) = a.array() - 0.5 * margin;
    b.hi.col(k) = c.array() + 0.5 * margin;
    const int body = tet_body[k];
    own[static_cast<std::size_t>(body)].push_back(k);
    body_lo.col(body) = body_lo.col(body).cwiseMin(b.lo.col(k));
    body_hi.col(body) = body_hi.col(body).cwiseMax(b.hi.col(k));
  }
  // Body pairs whose boxes meet, by a sweep along x over the bodies' boxes. For each, only the
  // tetrahedra inside the other body's box, swept along the longest side of the boxes'
  // intersection: a rock on a block meets it in a thin slab, so the sweep runs across the slab.
  std::vector<int> bodies(static_cast<std::size_t>(n_bodies));
  std::iota(bodies.begin(), bodies.end(), 0);
  std::sort(bodies.begin(), bodies.end(),
            [&](int i, int j) { return body_lo(0, i) < body_lo(0, j); });
  for (std::size_t s = 0; s < bodies.size(); ++s) {
    for (std::size_t t = s + 1; t < bodies.size(); ++t) {
      const int p = bodies[s], q = bodies[t];
      if (body_lo(0, q) > body_hi(0, p)) break;
      if (own[p].empty() || own[q].empty() || (body_fixed[p] && body_fixed[q])) continue;
      const Vec3 lo = body_lo.col(p).cwiseMax(body_lo.col(q));
      const Vec3 hi = body_hi.col(p).cwiseMin(body_hi.col(q));
      if ((lo.array() > hi.array()).any()) continue;
      Eigen::Index axis;
      (hi - lo).maxCoeff(&axis);
      const std::vector<int> near_p = near_box(b, own[p], body_lo.col(q), body_hi.col(q), axis);
      const std::vector<int> near_q = near_box(b, own[q], body_lo.col(p), body_hi.col(p), axis);
      sweep_two(b, near_p, near_q, axis, out);
    }
  }
  std::sort(out.begin(), out.end(), [](const TetPair& p, const TetPair& q) {
    return p.a < q.a || (p.a == q.a && p.b < q.b);
  });
  return out;
}

}  // namespace asperity::fdem
