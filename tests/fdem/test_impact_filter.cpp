// The filtered peak of summary.json (issue 11): a moving average over a twentieth of the contact
// removes ringing well above the contact frequency and leaves the pulse's own peak.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "solver/run/impact_measures.hpp"

namespace asperity::run {
namespace {

// A half-sine pulse F₀ sin(πt/T) plus ringing A sin(2π n t/T) (n = 0: none), `steps` steps over
// the contact and 10 after it, fed to the measures as a run feeds them.
ImpactMeasures half_sine(double f0, double ripple, int ripple_periods, int steps) {
  const double period = 0.01, dt = period / steps;
  ImpactMeasures im;
  im.start(-dt, Vec3::Zero(), -1e-6);
  for (int i = 0; i <= steps + 10; ++i) {
    const double t = i * dt;
    const bool in = t < period;
    const double phase = std::numbers::pi * t / period;
    const double f =
        in ? f0 * std::sin(phase) + ripple * std::sin(2 * ripple_periods * phase) : 0.0;
    im.add(t, Vec3(0, 0, std::max(f, 0.0)), in ? std::sin(phase) + 1e-9 : -1e-6);
  }
  return im;
}

// A half-sine pulse (Hertz's pulse is close to it) with ringing of 60 periods per contact: the
// window T/20 holds three whole ringing periods, which average to zero, and lowers the
// half-sine's peak by (π/40)²/6 = 0.10 %. Tolerances: 0.15 % for that and the step grid.
TEST(ImpactFilter, MovingAverageRemovesRingingAndKeepsThePulse) {
  const double f0 = 100, ripple = 8;
  const ImpactMeasures im = half_sine(f0, ripple, 60, 6000);
  EXPECT_NEAR(im.filtered_peak() / f0, 1.0, 1.5e-3);
  // Raw peak: F₀ + A near the top (the ripple's crest lies within a step of the pulse's).
  EXPECT_NEAR(im.peak_force / (f0 + ripple), 1.0, 2e-3);
  EXPECT_NEAR(im.ringing_amplitude(), ripple / f0, 3e-3);
}

// The filter's bias on a smooth pulse (kFilteredPeakBias*, impact_measures.hpp), against the
// pulse itself: a half-sine, whose filtered peak is exactly sinc(π/40) of its own (the mean of
// sin over ±T/40), and Hertz's impact integrated here (m δ'' = −K δ^{3/2}, velocity Verlet at
// 40 000 steps per contact). Tolerance 1e-5 of the peak: the τ⁴ term of the mean, (π/40)⁴/120 =
// 3e-7 for the half-sine and of that size for Hertz, the window's rounding to whole steps (1 in
// 2000 of w, 2e-6 of the peak) and Verlet's O(dt²) peak (1e-9), each well under it.
TEST(ImpactFilter, BiasOnSmoothPulsesIsTheDerivedOne) {
  {
    const double f0 = 100;
    const ImpactMeasures im = half_sine(f0, 0, 0, 40000);
    const double x = std::numbers::pi / 40;
    EXPECT_NEAR(kFilteredPeakBiasHalfSine, 1 - std::sin(x) / x, 4e-7);  // its τ⁴ term
    EXPECT_NEAR(im.filtered_peak() / f0, 1 - kFilteredPeakBiasHalfSine, 1e-5);
  }
  {
    // A 1 kg ball, K = 1e9 N/m^1.5, 1 m/s: δ_max = (5 m v² / (4 K))^{2/5}.
    const double m = 1, k = 1e9, v = 1;
    const double delta_max = std::pow(5 * m * v * v / (4 * k), 0.4);
    const double duration = contact::kHertzDurationFactor * delta_max / v;
    const double dt = duration / 40000;
    double d = 0, u = v, t = 0;  // overlap, its rate, time
    ImpactMeasures im;
    im.start(-dt, Vec3::Zero(), -1e-9);
    const auto force = [&](double x) { return x > 0 ? k * std::pow(x, 1.5) : 0.0; };
    double a = -force(d) / m;
    while (t < 1.01 * duration) {
      im.add(t, Vec3(0, 0, force(d)), d > 0 ? d : (t == 0 ? 1e-30 : d));
      u += 0.5 * dt * a;
      d += dt * u;
      a = -force(d) / m;
      u += 0.5 * dt * a;
      t += dt;
    }
    const double peak = k * std::pow(delta_max, 1.5);
    EXPECT_NEAR(im.contact_duration / duration, 1, 1e-4);  // the integration is Hertz's
    EXPECT_NEAR(im.filtered_peak() / peak, 1 - kFilteredPeakBiasHertz, 1e-5);
    EXPECT_GT(kFilteredPeakBiasHertz, kFilteredPeakBiasHalfSine);  // Hertz's peak is sharper
  }
}

}  // namespace
}  // namespace asperity::run
