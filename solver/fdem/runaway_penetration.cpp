// Runaway penetration (fdem/runaway_penetration.hpp).
#include "solver/fdem/runaway_penetration.hpp"

#include <algorithm>

#include "solver/contact/munjiza_potential.hpp"
#include "solver/core/format.hpp"

namespace asperity::fdem {

// Along the segment each barycentric coordinate is linear, so the part inside a tetrahedron is
// the interval where all four are ≥ 0.
bool path_meets_tets(const World& w, const Eigen::Matrix4Xi& tets, int node_begin, int node_end,
                     const Vec3& p0, const Vec3& p1) {
  const Vec3 seg_lo = p0.cwiseMin(p1), seg_hi = p0.cwiseMax(p1);
  const auto nodes = w.x.middleCols(node_begin, node_end - node_begin);
  if ((seg_hi.array() < nodes.rowwise().minCoeff().array()).any() ||
      (seg_lo.array() > nodes.rowwise().maxCoeff().array()).any()) {
    return false;
  }
  for (Eigen::Index k = 0; k < tets.cols(); ++k) {
    contact::TetNodes t;
    Vec3 lo = w.x.col(tets(0, k)), hi = lo;
    for (int i = 0; i < 4; ++i) {
      t[i] = w.x.col(tets(i, k));
      lo = lo.cwiseMin(t[i]), hi = hi.cwiseMax(t[i]);
    }
    if ((seg_hi.array() < lo.array()).any() || (seg_lo.array() > hi.array()).any()) continue;
    const Eigen::Vector4d l0 = contact::barycentric(t, p0), l1 = contact::barycentric(t, p1);
    double s_lo = 0, s_hi = 1;
    for (int i = 0; i < 4 && s_lo <= s_hi; ++i) {
      const double d = l1[i] - l0[i];  // L_i(s) = l0 + s d ≥ 0
      if (d > 0) {
        s_lo = std::max(s_lo, -l0[i] / d);
      } else if (d < 0) {
        s_hi = std::min(s_hi, -l0[i] / d);
      } else if (l0[i] < 0) {
        s_hi = -1;
      }
    }
    if (s_lo <= s_hi) return true;
  }
  return false;
}

RunawayPenetration::RunawayPenetration(const World& w, const WorldDef& def) {
  bodies_.resize(w.bodies.size());
  centre_before_.resize(w.bodies.size());
  for (std::size_t b = 0; b < w.bodies.size(); ++b) {
    BodyTets& bt = bodies_[b];
    bt.tets = def.bodies[b].mesh.tets.array() + w.bodies[b].node_begin;
    bt.node_begin = w.bodies[b].node_begin;
    bt.node_end = w.bodies[b].node_end;
    const Vec3 c = body_centre(w, static_cast<int>(b));
    bt.centre_inside_itself = w.bodies[b].kind != BodyKind::fixed &&
                              path_meets_tets(w, bt.tets, bt.node_begin, bt.node_end, c, c);
    centre_before_[b] = c;
  }
}

std::string RunawayPenetration::check(const World& w) {
  auto name = [&](int b) { return "\"" + w.bodies[b].name + "\""; };
  if (w.penetration >= kRunawayPenetration) {
    return "runaway penetration: bodies " + name(w.penetration_body_a) + " and " +
           name(w.penetration_body_b) + " overlap " + fmt(w.penetration) +
           " of the way to an element's centre (limit " + fmt(kRunawayPenetration) +
           ") at t = " + fmt(w.time) + " s";
  }
  for (std::size_t a = 0; a < bodies_.size(); ++a) {
    if (!bodies_[a].centre_inside_itself) continue;
    const Vec3 c = body_centre(w, static_cast<int>(a));
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      if (b != a && path_meets_tets(w, bodies_[b].tets, bodies_[b].node_begin, bodies_[b].node_end,
                                    centre_before_[a], c)) {
        return "runaway penetration: body " + name(static_cast<int>(a)) + " passed through " +
               name(static_cast<int>(b)) + " (its centre entered it) at t = " + fmt(w.time) + " s";
      }
    }
    centre_before_[a] = c;
  }
  return {};
}

}  // namespace asperity::fdem
