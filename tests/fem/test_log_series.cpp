// The vectorizable logarithm of the element loop (fem/log_series.hpp) against long double logl.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <random>

#include "solver/fem/log_series.hpp"
#include "solver/fem/neo_hookean_tet.hpp"

namespace asperity::fem {
namespace {

// |log_series(x) − ln x| in units of the last place of the double nearest ln x, with ln x from
// the 64-bit-mantissa logl (its own error, about 2⁻⁶⁴ relative, is 1/2000 of a double's ulp).
double ulps(double x) {
  const long double exact = logl(static_cast<long double>(x));
  const double nearest = static_cast<double>(exact);
  const double ulp = std::nextafter(std::fabs(nearest), INFINITY) - std::fabs(nearest);
  return static_cast<double>(std::fabs(static_cast<long double>(log_series(x)) - exact) /
                             static_cast<long double>(ulp));
}

// Faithful (< 1 ulp) over the whole normal range and densely near J = 1, where the element loop
// takes it (|J − 1| is a strain). Tolerance: the final rounding is 1/2 ulp and the correction
// s (f²/2 + R) adds a few roundings of a term at most 0.09 of the result (f ≥ ln(1 + f) − f²/2 …):
// 0.82 ulp was the largest of 6 M random points while writing it; the series' truncation is
// 1e-18 relative (the header), so a missing or wrong coefficient shows as thousands of ulps.
TEST(LogSeries, WithinOneUlpOfTheExactLogarithm) {
  std::mt19937_64 g(11);
  std::uniform_real_distribution<double> wide(-708, 709), strain(-0.4, 0.4), tiny(-1e-6, 1e-6);
  double worst = 0;
  for (int i = 0; i < 100000; ++i) {
    worst = std::max({worst, ulps(std::exp(wide(g))), ulps(1 + strain(g)), ulps(1 + tiny(g))});
  }
  for (const double x :
       {DBL_MIN, DBL_MAX, 0.5, 2.0, M_SQRT1_2, M_SQRT2, 1 + DBL_EPSILON, 1 - DBL_EPSILON / 2}) {
    worst = std::max(worst, ulps(x));
  }
  EXPECT_LT(worst, 1.0);
  EXPECT_EQ(log_series(1.0), 0.0);  // ln 1 = 0 exactly: f = 0, k = 0
}

// Exact where the answer is representable: ln 2^k = k ln 2 to the rounding of k·ln 2's two parts.
TEST(LogSeries, PowersOfTwoAreKTimesLn2) {
  for (int k = -1022; k <= 1023; k += 7) {
    const double x = std::ldexp(1.0, k);
    EXPECT_LT(ulps(x), 0.5 + 1e-9) << "2^" << k;  // correctly rounded: f = 0, only k·lo rounds
  }
}

// The element kernels' ln J: log_series where it is valid, std::log for subnormal J.
TEST(LogSeries, TheKernelFallsBackBeyondTheNormalRange) {
  EXPECT_EQ(tet_log_j(1.25), log_series(1.25));
  EXPECT_EQ(tet_log_j(DBL_MIN / 4), std::log(DBL_MIN / 4));
  EXPECT_FALSE(log_series_covers(0.0));
  EXPECT_FALSE(log_series_covers(INFINITY));
}

}  // namespace
}  // namespace asperity::fem
