// Critical-step prediction for the sphere world (formulas and sources in the header).
#include "solver/dem/time_step.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "solver/contact/hertz_impact.hpp"
#include "solver/core/central_difference.hpp"

namespace asperity::dem {

CriticalStep critical_step(const SphereWorld& w) {
  CriticalStep out;
  constexpr double inf = std::numeric_limits<double>::infinity();
  out.rayleigh = inf;
  double m_min = inf, r_max = 0, v_max = 0;
  for (int i = 0; i < w.size(); ++i) {
    if (w.fixed[i]) continue;
    const Material& m = w.materials[w.material[i]];
    const double dt_r = std::numbers::pi * w.radius[i] * std::sqrt(m.density / shear_modulus(m)) /
                        (0.1631 * m.poisson + 0.8766);
    out.rayleigh = std::min(out.rayleigh, dt_r);
    m_min = std::min(m_min, w.mass[i]);
    r_max = std::max(r_max, w.radius[i]);
    v_max = std::max(v_max, w.v.col(i).norm() + w.radius[i] * w.w.col(i).norm());
  }
  // Height of the scene along gravity: sphere centres and wall anchors.
  double height = 0;
  if (const double g = w.gravity.norm(); g > 0) {
    const Vec3 dir = w.gravity / g;
    double lo = inf, hi = -inf;
    auto span = [&](const Vec3& p) {
      lo = std::min(lo, p.dot(dir));
      hi = std::max(hi, p.dot(dir));
    };
    for (int i = 0; i < w.size(); ++i) span(w.x.col(i));
    for (const Wall& wall : w.walls) {
      span(wall.a);
      if (wall.kind == WallKind::box) span(wall.b);
    }
    height = hi - lo;
  }
  out.approach_speed = 2 * v_max + std::sqrt(2 * w.gravity.norm() * height);

  // Only pairs that can touch: a free sphere's material against any sphere's or wall's (two
  // walls never meet, and a stiff wall material against itself must not set the step).
  const int nm = static_cast<int>(w.materials.size());
  std::vector<char> free_material(nm, 0), any_material(nm, 0);
  for (int i = 0; i < w.size(); ++i) {
    any_material[w.material[i]] = 1;
    if (!w.fixed[i]) free_material[w.material[i]] = 1;
  }
  for (const Wall& wall : w.walls) any_material[wall.material] = 1;
  double young_max = 0, zeta_max = 0;
  for (int a = 0; a < nm; ++a) {
    for (int b = 0; b < nm; ++b) {
      if (!free_material[a] || !any_material[b]) continue;
      young_max = std::max(young_max, w.pair[a * nm + b].young_eff);
      zeta_max = std::max(zeta_max, w.pair[a * nm + b].zeta);
    }
  }
  out.contact = inf;
  if (m_min < inf) {
    const double m_eff = 0.5 * m_min;
    double omega = 0, xi = 0;
    if (w.law.normal == contact::NormalLaw::linear) {
      omega = std::sqrt(w.law.kn / m_eff);
      xi = 0.5 * zeta_max;
    } else if (out.approach_speed > 0) {
      const contact::HertzImpact h =
          contact::hertz_impact(m_eff, r_max, young_max, out.approach_speed);
      out.hertz_contact_time = h.contact_duration;
      const double k_max = 2.0 * young_max * std::sqrt(r_max * h.max_overlap);
      omega = std::sqrt(k_max / m_eff);
      xi = zeta_max / (2 * std::sqrt(1.5));
    }
    if (omega > 0) out.contact = damped_critical_step(omega, xi);
  }
  // Rigid spheres carry no elastic waves: the contact oscillator is the central-difference limit.
  // The Rayleigh step (a packing heuristic) bounds the step only when no contact can be sized.
  out.critical = std::isfinite(out.contact) ? out.contact : out.rayleigh;
  out.limited_by = std::isfinite(out.contact) ? "contact" : "rayleigh";
  return out;
}

}  // namespace asperity::dem
