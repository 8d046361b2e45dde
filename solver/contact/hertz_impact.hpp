// Closed-form elastic Hertz impact (Johnson 1985, Contact Mechanics, §11.4): the analytic
// reference the validation gates compare against; and Hertz's contact at a given force (§4.2):
// its radius, pressure and deepest shear, which the report's picture of a deformable sphere draws
// (app/hertz_numbers).
#pragma once

#include <cmath>
#include <numbers>

namespace asperity::contact {

// 2 ∫₀¹ dx / √(1 − x^{5/2}) = (4/5) B(2/5, 1/2) (Johnson 1985, eq. 11.24 quotes 2.94).
inline constexpr double kHertzDurationFactor = 2.9432751843;

struct HertzImpact {
  double max_overlap = 0;       // δ_max = (15 m* v² / (16 E* √R*))^{2/5}, m (Johnson eq. 11.23)
  double peak_force = 0;        // F_max = 4/3 E* √R* δ_max^{3/2}, N
  double contact_duration = 0;  // t_c = 2.9432 δ_max / v, s (Johnson eq. 11.24)
  double impulse = 0;           // ∫F dt = 2 m* v for an elastic impact, N·s
};

// m* (kg), R* (m), E* (Pa), approach speed v (m/s).
inline HertzImpact hertz_impact(double mass_eff, double radius_eff, double young_eff, double v) {
  HertzImpact h;
  h.max_overlap =
      std::pow(15.0 * mass_eff * v * v / (16.0 * young_eff * std::sqrt(radius_eff)), 0.4);
  h.peak_force = 4.0 / 3.0 * young_eff * std::sqrt(radius_eff) * std::pow(h.max_overlap, 1.5);
  h.contact_duration = kHertzDurationFactor * h.max_overlap / v;
  h.impulse = 2.0 * mass_eff * v;
  return h;
}

// The Hertz contact duration alone, s: t_c = 2.9432 δ_max / v = 2.868 (m*² / (R* E*² v))^{1/5}.
inline double hertz_contact_time(double mass_eff, double radius_eff, double young_eff, double v) {
  return hertz_impact(mass_eff, radius_eff, young_eff, v).contact_duration;
}

// Hertz's contact under a normal force F (Johnson 1985, §4.2): the contact circle's radius, the
// pressure at its centre, p(r) = p0 √(1 − r²/a²), and where the shear under it peaks.
struct HertzContact {
  double radius = 0;         // a = (3 F R* / (4 E*))^{1/3}, m
  double peak_pressure = 0;  // p0 = 3 F / (2π a²), Pa
  // The depth on the axis of the largest principal shear stress, τ1 = 0.31 p0 at z = 0.48 a, m
  // (Johnson 1985, §4.2, at ν = 0.3: the depth moves a little with ν, which this leaves out).
  double max_shear_depth = 0;
};

// F (N), R* (m), E* (Pa).
inline HertzContact hertz_contact(double force, double radius_eff, double young_eff) {
  HertzContact c;
  c.radius = std::pow(3.0 * force * radius_eff / (4.0 * young_eff), 1.0 / 3.0);
  c.peak_pressure = 3.0 * force / (2.0 * std::numbers::pi * c.radius * c.radius);
  c.max_shear_depth = 0.48 * c.radius;
  return c;
}

// Hertz's pressure at a distance r (m) from the contact's centre, Pa: p0 √(1 − r²/a²) inside the
// circle, 0 outside it.
inline double hertz_pressure(const HertzContact& c, double r) {
  const double x = r / c.radius;
  return x < 1 ? c.peak_pressure * std::sqrt(1 - x * x) : 0.0;
}

}  // namespace asperity::contact
