// The one least-squares line of the reports: the study's CPU cost against N (cpu_fit.csv), the
// collision cost's exponent over N (benchmarks/collision_cost.cpp) and the Hertz limits against
// a/R (benchmarks/hertz_rates.cpp). A power law t = C N^p is this line through (log N, log t).
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

namespace asperity {

// y = intercept + slope x by ordinary least squares over the points (x[i], y[i]), with the
// standard errors of both from the residuals, s² = Σ r² / (n − 2) (NaN for two points, which the
// line passes through). Needs at least two distinct x; x and y of one length.
struct LineFit {
  double intercept = std::nan(""), slope = std::nan("");
  double intercept_error = std::nan(""), slope_error = std::nan("");
  long points = 0;
};

inline LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  const double count = static_cast<double>(n);
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n; ++i) mx += x[i] / count, my += y[i] / count;
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < n; ++i)
    sxy += (x[i] - mx) * (y[i] - my), sxx += (x[i] - mx) * (x[i] - mx);
  LineFit f{.slope = sxy / sxx, .points = static_cast<long>(n)};
  f.intercept = my - f.slope * mx;
  if (n > 2) {
    double ss = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double r = y[i] - f.intercept - f.slope * x[i];
      ss += r * r;
    }
    const double s2 = ss / (count - 2);
    f.intercept_error = std::sqrt(s2 * (1 / count + mx * mx / sxx));
    f.slope_error = std::sqrt(s2 / sxx);
  }
  return f;
}

}  // namespace asperity
