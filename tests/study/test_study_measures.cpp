// Known answers for the study's curve measures: skewness, cross-correlation lag, classes,
// quantiles and their spread, and the Hertz contact time.
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "solver/core/least_squares.hpp"
#include "solver/core/quantile.hpp"
#include "study/curve_measures.hpp"
#include "study/study_run.hpp"

namespace asperity::study {
namespace {

// A half-sine pulse of length d starting at t0, sampled every h over [0, t_end].
void pulse(double t0, double d, double t_end, double h, std::vector<double>& t,
           std::vector<double>& f, double lean = 0) {
  t.clear();
  f.clear();
  for (double x = 0; x <= t_end + 1e-15; x += h) {
    t.push_back(x);
    const double u = (x - t0) / d;
    // lean > 0 stretches the fall: u' = u^(1-lean) moves the peak earlier
    f.push_back(u > 0 && u < 1 ? std::sin(std::numbers::pi * std::pow(u, 1 - lean)) : 0.0);
  }
}

std::size_t first_nonzero(const std::vector<double>& f) {
  std::size_t i = 0;
  while (i < f.size() && f[i] <= 0) ++i;
  return i;
}

TEST(CurveShape, HalfSineIsSymmetric) {
  std::vector<double> t, f;
  pulse(1e-4, 2e-4, 5e-4, 1e-7, t, f);
  const CurveShape s = curve_shape(t, f);
  EXPECT_NEAR(s.mean_time, 2e-4, 1e-9);  // the centre of the pulse
  EXPECT_NEAR(s.skewness, 0.0, 1e-6);    // symmetric: third moment 0 up to the quadrature
  // σ² of t under sin(πu) on [0, d]: d² (1/4 − 2/π²)
  EXPECT_NEAR(s.spread, 2e-4 * std::sqrt(0.25 - 2 / (std::numbers::pi * std::numbers::pi)), 1e-9);
}

TEST(CurveShape, EarlyPeakIsPositivelySkewed) {
  std::vector<double> t, f;
  pulse(1e-4, 2e-4, 5e-4, 1e-7, t, f, 0.5);
  EXPECT_GT(curve_shape(t, f).skewness, 0.3);  // a long fall: a tail to the right
}

TEST(CrossCorrelation, RecoversAShift) {
  std::vector<double> tr, fr, t, f;
  pulse(1.0e-4, 2e-4, 6e-4, 1e-7, tr, fr);
  pulse(1.37e-4, 2e-4, 6e-4, 3e-7, t, f);  // later by 37 µs, sampled differently
  // grid 6e-4/2047 ≈ 0.29 µs; the parabola refines to well below one sample
  EXPECT_NEAR(cross_correlation_lag(tr, fr, t, f, 6e-4), 3.7e-5, 1e-7);
  EXPECT_NEAR(cross_correlation_lag(t, f, tr, fr, 6e-4), -3.7e-5, 1e-7);
}

TEST(Classify, Criteria) {
  EXPECT_EQ(classify(0.01, 1.02, 0.1), "overlapping");
  EXPECT_EQ(classify(0.06, 1.0, 0.0), "shifted");
  EXPECT_EQ(classify(-0.06, 1.0, 0.0), "shifted");
  EXPECT_EQ(classify(0.0, 1.2, 0.0), "tail");
  EXPECT_EQ(classify(0.0, 0.8, 0.0), "short");
  EXPECT_EQ(classify(0.0, 1.0, -0.4), "asymmetric");
  EXPECT_EQ(classify(0.1, 1.2, 0.4), "shifted+tail+asymmetric");
  EXPECT_EQ(classify(0.1, 0.7, 0.0), "shifted+short");
}

// Why "shifted" is read from the first-contact time, not the cross-correlation lag: a
// half-sine pulse 30 % shorter that starts at the same instant is a stiffer response, not a
// shifted one, yet the lag that best aligns the two is about half the width difference (for
// two half-sines of widths 1 and 0.7, their centres differ by 0.15 of the reference width).
TEST(Classify, AShorterPulseThatStartsTogetherIsShortNotShifted) {
  std::vector<double> tr, fr, t, f;
  pulse(1.0e-4, 2e-4, 6e-4, 1e-7, tr, fr);
  pulse(1.0e-4, 1.4e-4, 6e-4, 1e-7, t, f);
  const double lag_rel = cross_correlation_lag(tr, fr, t, f, 6e-4) / 2e-4;
  // Symmetric pulses align at their centres: 1.7e-4 against 2e-4, −0.15 of the reference width
  // (to the grid's 0.29 µs = 0.0015 and the parabola's refinement).
  EXPECT_NEAR(lag_rel, -0.15, 0.003);  // the lag alone would call it "shifted" (> 0.05)
  const double onset_rel = (t[first_nonzero(f)] - tr[first_nonzero(fr)]) / 2e-4;
  EXPECT_EQ(classify(onset_rel, 0.7, 0.0), "short");
}

TEST(Quantile, Type7) {
  EXPECT_DOUBLE_EQ(quantile({3, 1, 2}, 0.5), 2.0);
  EXPECT_DOUBLE_EQ(quantile({1, 2, 3, 4}, 0.5), 2.5);
  EXPECT_DOUBLE_EQ(quantile({0, 10}, 0.9), 9.0);
}

TEST(Quantile, Spread) {
  // Five repeats in any order: the middle one and the extremes, exactly (no arithmetic on them).
  const Spread five = spread({4.5, 2.8, 3.7, 7.5, 0.1});
  EXPECT_EQ(five.count, 5u);
  EXPECT_EQ(five.median, 3.7);
  EXPECT_EQ(five.min, 0.1);
  EXPECT_EQ(five.max, 7.5);
  // An even count: the type-7 mean of the two middle ones, 2 + 0.5 (3 - 2), exact in binary.
  EXPECT_EQ(spread({3, 1, 2, 4}).median, 2.5);
  // No repeat: nothing to summarize, NaN rather than a made-up number.
  const Spread none = spread({});
  EXPECT_EQ(none.count, 0u);
  EXPECT_TRUE(std::isnan(none.median) && std::isnan(none.min) && std::isnan(none.max));
}

TEST(LeastSquares, LineAndErrors) {
  // Exactly on y = 1 + 2x: no residual, no error.
  const LineFit exact = fit_line({0, 1, 2}, {1, 3, 5});
  EXPECT_DOUBLE_EQ(exact.intercept, 1.0);
  EXPECT_DOUBLE_EQ(exact.slope, 2.0);
  EXPECT_DOUBLE_EQ(exact.slope_error, 0.0);
  EXPECT_EQ(exact.points, 3);
  // (0, 0), (1, 1), (2, 0), (3, 1): slope 0.2, intercept 0.2, residuals −0.2, 0.6, −0.6, 0.2:
  // s² = 0.8/2, Sxx = 5.
  const LineFit noisy = fit_line({0, 1, 2, 3}, {0, 1, 0, 1});
  EXPECT_NEAR(noisy.slope, 0.2, 1e-15);
  EXPECT_NEAR(noisy.intercept, 0.2, 1e-15);
  EXPECT_NEAR(noisy.slope_error, std::sqrt(0.4 / 5), 1e-15);
  EXPECT_NEAR(noisy.intercept_error, std::sqrt(0.4 * (0.25 + 2.25 / 5)), 1e-15);
  // Two points: the line through them, no error estimate.
  EXPECT_TRUE(std::isnan(fit_line({1, 2}, {1, 2}).slope_error));
}

}  // namespace
}  // namespace asperity::study
