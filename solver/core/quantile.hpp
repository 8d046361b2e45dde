// The one quantile of every table that reports a median or a percentile: the study's tables
// (study/tables/), the penalty summary, the collision cost, the peer cost, and the median and
// spread of repeated measurements (app/spread_table: the performance record, the peer table, the
// schedule estimate, the cluster scaling). Written once here so that no report computes a median
// its own way (Python's statistics.median included: the reports read these).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace asperity {

// p-th quantile (0..1) with linear interpolation between order statistics (Hyndman & Fan type 7);
// NaN for no values. At p = 0.5 the median: the middle value, or the mean of the two middle ones.
inline double quantile(std::vector<double> v, double p) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const double h = p * static_cast<double>(v.size() - 1);
  const std::size_t lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (h - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

// A repeated measurement summarized: how many samples, their median and their spread.
struct Spread {
  std::size_t count = 0;
  double median = std::nan("");  // quantile(v, 0.5)
  double min = std::nan("");
  double max = std::nan("");
};

// NaN median and bounds for no values.
inline Spread spread(const std::vector<double>& v) {
  Spread s{.count = v.size(), .median = quantile(v, 0.5)};
  if (!v.empty()) {
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    s.min = *lo;
    s.max = *hi;
  }
  return s;
}

}  // namespace asperity
