// Measures of the recorded body's contact history, derived above the worlds from their per-step
// contact output (core/body_contacts.hpp): the same code for spheres, FEM/DEM and the peers.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "solver/contact/hertz_impact.hpp"
#include "solver/core/vec.hpp"

namespace asperity::run {

// How much the filtered peak (ImpactMeasures::filtered_peak) lowers a smooth pulse of duration T:
// a centred mean over w = T/20 of F(t_p + τ) ≈ F (1 − κ τ² / 2) is F (1 − κ w² / 24).
// - Half-sine, κ = π² / T²: (π/40)² / 6 = 0.103 %.
// - Hertz's impact (Johnson 1985, §11.4): F = K δ^{3/2} with m δ'' = −F, so at the peak (δ' = 0)
//   F'' / F = (3/2) δ'' / δ_max = −(3/2) F_max / (m δ_max), and the energy ½ m v² = (2/5) F_max
//   δ_max gives κ = (15/8) v² / δ_max² = (15/8) c² / T², c = T v / δ_max = kHertzDurationFactor:
//   (15/8) c² / 9600 = 0.169 %.
// A pulse between the two shapes (a finite or rough body) lies within their difference, 0.066 %.
inline constexpr double kFilteredPeakBiasHalfSine = std::numbers::pi * std::numbers::pi / 9600.0;
inline constexpr double kFilteredPeakBiasHertz =
    15.0 / 8.0 * contact::kHertzDurationFactor * contact::kHertzDurationFactor / 9600.0;

// Fed once per step with the recorded body's total contact force and its largest signed
// overlap s (m; negative while apart). Contact starts and ends are placed by linear
// interpolation of s between steps, so the duration is second-order accurate in dt rather than
// rounded to whole steps.
struct ImpactMeasures {
  double peak_force = 0;           // N
  double impulse = 0;              // ∫|F| dt, trapezoidal, N·s
  double contact_duration = 0;     // s, time with s > 0
  double first_contact_time = -1;  // s, -1: none
  double max_overlap = 0;          // m
  double last_separation = -1;     // s, when the latest contact ended; -1: none ended yet
  bool touching = false;

  // The first contact's force magnitude at every step, kept to filter its peak (filtered_peak).
  std::vector<double> first_contact_force;

  void start(double t, const Vec3& f, double s) {
    t_prev_ = t;
    f_prev_ = f.norm();
    s_prev_ = s;
    touching = s > 0;
    if (touching) {
      first_contact_time = t;
      contact_start_ = t;
    }
    peak_force = f_prev_;
  }

  void add(double t, const Vec3& f, double s) {
    const double fm = f.norm();
    peak_force = std::max(peak_force, fm);
    if (touching && last_separation < 0) first_contact_force.push_back(fm);  // first contact
    impulse += 0.5 * (fm + f_prev_) * (t - t_prev_);
    if (s > 0) max_overlap = std::max(max_overlap, s);
    if (!touching && s > 0) {
      contact_start_ = crossing(t, s);
      if (first_contact_time < 0) first_contact_time = contact_start_;
      touching = true;
    } else if (touching && s <= 0) {
      last_separation = crossing(t, s);
      contact_duration += last_separation - contact_start_;
      touching = false;
    }
    t_prev_ = t;
    f_prev_ = fm;
    s_prev_ = s;
  }

  // True once a contact has ended and none has started for `window` s (record
  // end_after_separation): the impact is over and the run may stop.
  bool separated_for(double t, double window) const {
    return !touching && last_separation >= 0 && t - last_separation >= window;
  }

  // Peak of the first contact's force after a centred moving average over a twentieth of that
  // contact's duration (issue 11): a low-pass tied to the contact time that removes the ringing
  // of the highest element modes and lowers a smooth pulse's peak by κ w² / 24 (κ = |F''| / F at
  // the peak, w = T / 20): kFilteredPeakBiasHalfSine for a half-sine, kFilteredPeakBiasHertz for
  // Hertz's pulse (below). 0 before any contact.
  double filtered_peak() const {
    const std::size_t n = first_contact_force.size();
    if (n == 0) return 0;
    const auto w = std::max<std::size_t>(1, std::min(n, n / 20));
    double sum = 0, best = 0;
    for (std::size_t i = 0; i < n; ++i) {
      sum += first_contact_force[i];
      if (i >= w) sum -= first_contact_force[i - w];
      if (i + 1 >= w) best = std::max(best, sum / static_cast<double>(w));
    }
    return best;
  }
  // Raw / filtered peak − 1 of the first contact: how much of its peak is ringing. 0 before any
  // contact.
  double ringing_amplitude() const {
    const double filtered = filtered_peak();
    if (filtered <= 0) return 0;
    return *std::max_element(first_contact_force.begin(), first_contact_force.end()) / filtered - 1;
  }

  // Contact still open at the end counts up to `t_end`.
  double duration_until(double t_end) const {
    return contact_duration + (touching ? t_end - contact_start_ : 0.0);
  }

 private:
  double crossing(double t, double s) const {
    // s_prev is -huge when no candidate contact existed the step before: no interpolation.
    if (!(s_prev_ > -1e200) || s == s_prev_) return t;
    const double frac = -s_prev_ / (s - s_prev_);
    return t_prev_ + std::clamp(frac, 0.0, 1.0) * (t - t_prev_);
  }
  double t_prev_ = 0, f_prev_ = 0, s_prev_ = -1e300, contact_start_ = 0;
};

// Restitution of the recorded body's first contact, one definition for every model and peer:
//   e = (v_sep · n) / (−v_app · n),
// v the recorded body's centre velocity relative to its partner's (run::restitution_partner)
// just before the first contact began and just after it ended, n the direction of the normal
// impulse on the recorded body over that contact (the elastic or potential force plus normal
// damping; friction excluded, so an oblique frictional impact still measures the normal
// rebound). Whichever body is recorded (the moving one, or the block it strikes) the value is the
// same. For rigid spheres, whose centre velocities carry the whole normal motion, this is the
// usual ratio of normal separation and approach speeds.
class Restitution {
 public:
  // Once per step: whether the recorded body touched before and after the step, the relative
  // velocity before and after it, and the normal force on the recorded body after it.
  void add(bool touching_before, bool touching_after, const Vec3& v_before, const Vec3& v_after,
           const Vec3& normal_force, double dt) {
    if (ended_) return;
    if (!started_ && touching_after) {
      started_ = true;
      v_approach_ = touching_before ? v_after : v_before;
    }
    if (started_ && touching_after) normal_impulse_ += normal_force * dt;
    if (started_ && touching_before && !touching_after) {
      v_separation_ = v_after;
      ended_ = true;
    }
  }
  // Empty while the first contact has not ended, or when nothing approached.
  std::optional<double> value() const {
    if (!ended_ || !(normal_impulse_.norm() > 0)) return std::nullopt;
    const Vec3 n = normal_impulse_.normalized();
    const double in = -v_approach_.dot(n);
    if (!(in > 0)) return std::nullopt;
    return v_separation_.dot(n) / in;
  }
  bool ended() const { return ended_; }

 private:
  bool started_ = false, ended_ = false;
  Vec3 v_approach_ = Vec3::Zero(), v_separation_ = Vec3::Zero();
  Vec3 normal_impulse_ = Vec3::Zero();
};

// The partner whose velocity the restitution is measured against (`free`: whether each body
// moves): for a moving recorded body, the other moving body when there are exactly two, else the
// fixed targets (−1: velocity zero); for a fixed recorded body, the one moving body (−1 when
// there are several: no single rebound to measure against it).
inline int restitution_partner(int record, const std::vector<bool>& free) {
  std::vector<int> moving;
  for (std::size_t b = 0; b < free.size(); ++b) {
    if (free[b]) moving.push_back(static_cast<int>(b));
  }
  if (free[static_cast<std::size_t>(record)]) {
    if (moving.size() == 2) return moving[0] == record ? moving[1] : moving[0];
    return -1;
  }
  return moving.size() == 1 ? moving[0] : -1;
}

}  // namespace asperity::run
