// The filtered peak of summary.json (issue 11): a moving average over a twentieth of the contact
// removes ringing well above the contact frequency and leaves the pulse's own peak.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "solver/run/impact_measures.hpp"

namespace asperity::run {
namespace {

// A half-sine pulse F₀ sin(πt/T) (Hertz's pulse is close to it) with ringing A sin(2π 60 t/T):
// the window T/20 holds three whole ringing periods, which average to zero, and lowers the
// half-sine's peak by (π/40)²/6 = 0.10 %. Tolerances: 0.15 % for that and the step grid.
TEST(ImpactFilter, MovingAverageRemovesRingingAndKeepsThePulse) {
  const double f0 = 100, ripple = 8, period = 0.01;
  const int steps = 6000;
  const double dt = period / steps;
  ImpactMeasures im;
  im.start(-dt, Vec3::Zero(), -1e-6);
  for (int i = 0; i <= steps + 10; ++i) {
    const double t = i * dt;
    const bool in = t < period;
    const double phase = std::numbers::pi * t / period;
    const double f = in ? f0 * std::sin(phase) + ripple * std::sin(120 * phase) : 0.0;
    im.add(t, Vec3(0, 0, std::max(f, 0.0)), in ? std::sin(phase) + 1e-9 : -1e-6);
  }
  EXPECT_NEAR(im.filtered_peak() / f0, 1.0, 1.5e-3);
  // Raw peak: F₀ + A near the top (the ripple's crest lies within a step of the pulse's).
  EXPECT_NEAR(im.peak_force / (f0 + ripple), 1.0, 2e-3);
  EXPECT_NEAR(im.ringing_amplitude(), ripple / f0, 3e-3);
}

}  // namespace
}  // namespace asperity::run
