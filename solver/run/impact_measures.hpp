// Measures of the recorded body's force history, shared by every model's runner.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/vec.hpp"

namespace asperity::run {

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
  // of the highest element modes and lowers a half-sine pulse's peak by only (π/40)²/6 ≈ 0.1 %.
  // 0 before any contact.
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

}  // namespace asperity::run
