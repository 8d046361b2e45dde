// The study's curve measures (curve_measures.hpp).
#include "study/curve_measures.hpp"

#include <algorithm>
#include <cmath>

namespace asperity::study {

CurveShape curve_shape(const std::vector<double>& t, const std::vector<double>& f) {
  // Trapezoidal moments of t under the weight f.
  double m0 = 0, m1 = 0;
  for (std::size_t i = 1; i < t.size(); ++i) {
    const double h = t[i] - t[i - 1];
    m0 += 0.5 * h * (f[i] + f[i - 1]);
    m1 += 0.5 * h * (t[i] * f[i] + t[i - 1] * f[i - 1]);
  }
  CurveShape s;
  if (!(m0 > 0)) return s;
  s.mean_time = m1 / m0;
  double m2 = 0, m3 = 0;
  for (std::size_t i = 1; i < t.size(); ++i) {
    const double h = t[i] - t[i - 1], a = t[i] - s.mean_time, b = t[i - 1] - s.mean_time;
    m2 += 0.5 * h * (a * a * f[i] + b * b * f[i - 1]);
    m3 += 0.5 * h * (a * a * a * f[i] + b * b * b * f[i - 1]);
  }
  s.spread = std::sqrt(m2 / m0);
  s.skewness = s.spread > 0 ? m3 / m0 / (s.spread * s.spread * s.spread) : 0;
  return s;
}

namespace {

std::vector<double> resample(const std::vector<double>& t, const std::vector<double>& f,
                             double t_end, int n) {
  std::vector<double> out(n, 0.0);
  std::size_t j = 0;
  for (int i = 0; i < n; ++i) {
    const double x = t_end * i / (n - 1);
    while (j + 1 < t.size() && t[j + 1] < x) ++j;
    if (t.empty() || x < t.front() || x > t.back()) continue;
    if (j + 1 >= t.size()) {
      out[i] = f.back();
    } else {
      const double h = t[j + 1] - t[j];
      const double w = h > 0 ? (x - t[j]) / h : 0;
      out[i] = (1 - w) * f[j] + w * f[j + 1];
    }
  }
  return out;
}

}  // namespace

double cross_correlation_lag(const std::vector<double>& t_ref, const std::vector<double>& ref,
                             const std::vector<double>& t, const std::vector<double>& f,
                             double t_end, int points) {
  const std::vector<double> a = resample(t_ref, ref, t_end, points),
                            b = resample(t, f, t_end, points);
  const int max_lag = points / 2;
  std::vector<double> c(2 * max_lag + 1, 0.0);
  for (int k = -max_lag; k <= max_lag; ++k) {
    double s = 0;
    for (int i = std::max(0, -k); i < points && i + k < points; ++i) s += a[i] * b[i + k];
    c[k + max_lag] = s;
  }
  const int best = static_cast<int>(std::max_element(c.begin(), c.end()) - c.begin());
  double shift = best - max_lag;
  if (best > 0 && best + 1 < static_cast<int>(c.size())) {
    // Vertex of the parabola through the peak and its neighbours: sub-sample lag.
    const double l = c[best - 1], m = c[best], r = c[best + 1], den = l - 2 * m + r;
    if (den < 0) shift += 0.5 * (l - r) / den;
  }
  return shift * t_end / (points - 1);
}

std::string classify(double onset_shift_rel, double duration_ratio, double skew_diff,
                     const ClassifyCriteria& c) {
  std::string out;
  auto add = [&](const char* s) {
    if (!out.empty()) out += '+';
    out += s;
  };
  if (std::abs(onset_shift_rel) > c.shift) add("shifted");
  if (duration_ratio > c.tail) add("tail");
  if (duration_ratio < c.shortened) add("short");
  if (std::abs(skew_diff) > c.asymmetry) add("asymmetric");
  return out.empty() ? "overlapping" : out;
}

}  // namespace asperity::study
