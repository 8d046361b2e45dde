// Rebound measures of the recorded sphere (formulas and sign conventions in the header).
#include "solver/run/rebound.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace asperity::run {
namespace {

struct Motion {
  Vec3 x = Vec3::Zero(), v = Vec3::Zero(), w = Vec3::Zero();
  double radius = 0;  // 0: not a sphere (a plane or box: the arm to its contact point is 0)
};

Motion initial_motion(const scene::BodyDef& b) {
  Motion m;
  m.x = b.position;
  if (!b.fixed) {
    m.v = b.velocity;
    m.w = b.angular_velocity;
  }
  if (const auto* s = std::get_if<scene::SphereShape>(&b.shape)) m.radius = s->radius;
  return m;
}

// Signed gap between the recorded sphere (centre x, radius r) and a fixed box, and its normal.
double box_gap(const scene::BoxShape& bx, const Vec3& x, double r, Vec3& normal) {
  const Vec3 c = x.cwiseMax(bx.min).cwiseMin(bx.max);
  const Vec3 d = x - c;
  const double dist = d.norm();
  if (dist == 0) return -r;
  normal = d / dist;
  return dist - r;
}

double rad_to_deg(double a) {
  return a * 180.0 / std::numbers::pi;
}

}  // namespace

std::optional<FirstImpact> first_impact(const scene::SceneDef& s) {
  if (s.gravity.norm() != 0 || s.record.body < 0) return std::nullopt;
  const scene::BodyDef& rb = s.bodies[s.record.body];
  const auto* rs = std::get_if<scene::SphereShape>(&rb.shape);
  if (!rs || rb.fixed) return std::nullopt;
  const Motion r = initial_motion(rb);
  FirstImpact best;
  best.time = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < s.bodies.size(); ++k) {
    if (static_cast<int>(k) == s.record.body) continue;
    const scene::BodyDef& b = s.bodies[k];
    double t = std::numeric_limits<double>::infinity();
    Vec3 n = Vec3::UnitZ();
    if (const auto* sb = std::get_if<scene::SphereShape>(&b.shape)) {
      const Motion o = initial_motion(b);
      // |p + u t| = R + R_b, the earlier root.
      const Vec3 p = r.x - o.x, u = r.v - o.v;
      const double a = u.squaredNorm(), bq = 2 * p.dot(u),
                   c = p.squaredNorm() - std::pow(rs->radius + sb->radius, 2);
      const double disc = bq * bq - 4 * a * c;
      if (a > 0 && disc >= 0) {
        const double root = (-bq - std::sqrt(disc)) / (2 * a);
        if (root >= 0) {
          t = root;
          n = (p + u * t).normalized();
        }
      }
    } else if (const auto* pl = std::get_if<scene::PlaneShape>(&b.shape)) {
      const double gap = (r.x - pl->point).dot(pl->normal) - rs->radius, vn = r.v.dot(pl->normal);
      if (vn < 0 && gap >= 0) {
        t = gap / -vn;
        n = pl->normal;
      }
    } else if (const auto* bx = std::get_if<scene::BoxShape>(&b.shape)) {
      // March in steps of a twentieth of the radius, then bisect the first sign change.
      const double speed = r.v.norm();
      if (speed > 0) {
        const double h = 0.05 * rs->radius / speed;
        double t0 = 0;
        Vec3 dummy;
        double g0 = box_gap(*bx, r.x, rs->radius, dummy);
        for (double t1 = h; t1 <= s.duration + h && g0 > 0; t1 += h) {
          const double g1 = box_gap(*bx, r.x + r.v * t1, rs->radius, dummy);
          if (g1 <= 0) {
            double lo = t0, hi = t1;
            for (int it = 0; it < 100; ++it) {
              const double mid = 0.5 * (lo + hi);
              (box_gap(*bx, r.x + r.v * mid, rs->radius, dummy) > 0 ? lo : hi) = mid;
            }
            t = hi;
            box_gap(*bx, r.x + r.v * lo, rs->radius, n);
            break;
          }
          t0 = t1;
          g0 = g1;
        }
      }
    }
    if (t < best.time) {
      best.time = t;
      best.partner = static_cast<int>(k);
      best.normal = n;
    }
  }
  if (best.partner < 0 || best.time > s.duration) return std::nullopt;
  return best;
}

void add_rebound_measures(const scene::SceneDef& s, const FirstImpact& impact,
                          const BodyMotion& record_end, const BodyMotion& partner_end,
                          bool separated, nlohmann::ordered_json& j) {
  const Motion r = initial_motion(s.bodies[s.record.body]);
  const Motion p = initial_motion(s.bodies[impact.partner]);
  const Vec3& n = impact.normal;
  // Contact-point velocity of the recorded sphere relative to the partner's, arms at full radii.
  auto slip = [&](const Vec3& vr, const Vec3& wr, const Vec3& vp, const Vec3& wp) -> Vec3 {
    return (vr + wr.cross(-r.radius * n)) - (vp + wp.cross(p.radius * n));
  };
  auto tangential = [&](const Vec3& a) -> Vec3 { return a - a.dot(n) * n; };
  const Vec3 v_in = r.v - p.v;
  const Vec3 slip_in = tangential(slip(r.v, r.w, p.v, p.w));
  const Vec3 vt_in = tangential(v_in);
  // A slip or tangential speed below 1e-9 of the impact's speed scale counts as none.
  const double scale = v_in.norm() + r.radius * r.w.norm() + p.radius * p.w.norm();
  std::optional<Vec3> t_hat;
  if (slip_in.norm() > 1e-9 * scale)
    t_hat = slip_in.normalized();
  else if (vt_in.norm() > 1e-9 * scale)
    t_hat = vt_in.normalized();

  j["impact_partner"] = s.bodies[impact.partner].name;
  j["normal_velocity_in"] = -v_in.dot(n);
  const Vec3 v_out = record_end.v - partner_end.v;
  if (separated) {
    j["normal_velocity_out"] = v_out.dot(n);
    j["angular_velocity_change"] = (record_end.w - r.w).norm();
    j["tangential_speed_out"] = tangential(v_out).norm();
  }
  if (!t_hat) return;
  const Vec3 spin_axis = n.cross(*t_hat);
  const double vt = v_in.dot(*t_hat), st = slip_in.dot(*t_hat);
  j["tangential_velocity_in"] = vt;
  j["slip_velocity_in"] = st;
  j["spin_in"] = r.w.dot(spin_axis);
  j["incident_angle_deg"] = rad_to_deg(std::atan2(vt, -v_in.dot(n)));
  if (!separated) return;
  const double vt_out = v_out.dot(*t_hat);
  const double st_out = slip(record_end.v, record_end.w, partner_end.v, partner_end.w).dot(*t_hat);
  j["tangential_velocity_out"] = vt_out;
  j["slip_velocity_out"] = st_out;
  j["spin_out"] = record_end.w.dot(spin_axis);
  if (std::abs(vt) > 1e-9 * scale) j["tangential_restitution"] = vt_out / vt;
  if (std::abs(st) > 1e-9 * scale) j["slip_ratio"] = st_out / st;
  j["rebound_angle_deg"] = rad_to_deg(std::atan2(st_out, v_out.dot(n)));
}

}  // namespace asperity::run
