// Richardson extrapolation of three levels refined by one constant ratio: the observed order and
// the finest level's own discretization error (Roache 1998, "Verification and Validation in
// Computational Science", ch. 5). Written once here for the convergence reports: the Hertz gates
// and their table (scenes/hertz_series.hpp, benchmarks/hertz_rates.cpp), the finite-sphere
// reference's tables (validation/reference/finite_sphere*_table.cpp).
//
// The study's rule is another: study/tables/study_cases.hpp `tables::richardson` takes any
// descending sizes (its order by bisection), trusts an observed order only within a range and
// otherwise extrapolates the two finest levels over an assumed bracket, with Roache's safety
// factor on the error; these reports print the order the levels show, whatever it is.
#pragma once

#include <algorithm>
#include <cmath>

namespace asperity {

// With levels e1, e2, e3 (coarse to fine, each refined by r) converging as e = L + c h^p, the
// changes fall by q = (e1 − e2)/(e2 − e3) = r^p.
struct RichardsonRate {
  double order = std::nan("");         // p = log q / log r
  double finest_error = std::nan("");  // e3 − L = (e2 − e3)/(q − 1): the finest level's own error
  double limit = std::nan("");         // L = e3 − finest_error
};

// From the ratio q of the successive changes and the two finest levels. The finite sphere's
// dynamic table passes |q|, so that levels whose changes alternate in sign still show the order of
// their magnitudes (finite_sphere_dynamic_table.cpp); everything else passes q itself.
// No order (NaN) where q ≤ 0: changes that alternate in sign, or a first change of zero.
inline RichardsonRate richardson_from_ratio(double q, double e2, double e3, double r) {
  const double finest = (e2 - e3) / (q - 1);
  return {.order = q > 0 ? std::log(q) / std::log(r) : std::nan(""),
          .finest_error = finest,
          .limit = e3 - finest};
}

// Three levels e1, e2, e3, coarse to fine, refined by the ratio r each.
inline RichardsonRate richardson_rate(double e1, double e2, double e3, double r) {
  return richardson_from_ratio((e1 - e2) / (e2 - e3), e2, e3, r);
}

// The orders at which an observed order is believed (Roache 1998, ch. 5: Richardson's limit holds
// only in the asymptotic range, and an observed order far from the formal one says the levels are
// not in it). Above: 4-node tetrahedra converge at about order 2 in displacement-driven quantities
// on smooth solutions, and the graded FEM contact measured 1.2-2.7 in peak force and 1.2-3.2 in
// duration (reports/fem/hertz_convergence.md); an order above 5 (changes falling 5.7 times per
// level at r = √2) is a stall or noise in the last change, not a rate. Below: the particles'
// vertex contacts converge at order 0.9-1 (reports/peers/calculix/README.md); under 0.5 the limit
// would lie more than 5.3 last changes beyond the finest level, farther than three levels can
// vouch for. The study's rule reads the same range (study/tables/study_cases.hpp,
// kObservedOrderMin/Max).
inline constexpr double kTrustedOrderMin = 0.5, kTrustedOrderMax = 5.0;
// Where the order is not trusted: Roache's grid convergence index of the two finest levels at the
// formal order, Fs |e2 − e3|/(r^p − 1), with Fs = 3 (Roache 1998, ch. 5: 3 for two levels or an
// assumed order, 1.25 only where three levels observe it) and p = 2 (linear tetrahedra). At
// r = √2 that is 3 last changes: the distance to the limit at any order above 0.83 (1 last change
// at order 2, 2.4 at order 1, the particles' order), not a claim that the levels converge at 2.
inline constexpr double kUntrustedSafety = 3.0, kFormalOrder = 2.0;
// That band in last changes at the refinement ratio r: Fs / (r^p − 1), never below 1 (3 at √2,
// 1 at 2).
inline double untrusted_band(double r) {
  return std::max(1.0, kUntrustedSafety / (std::pow(r, kFormalOrder) - 1));
}

// A cross-check's estimate from three levels (asperity's against a peer's:
// tests/peers/test_calculix.cpp): where the observed order lies in
// [kTrustedOrderMin, kTrustedOrderMax], Richardson's limit with its finest level's distance from
// it as the error; otherwise (alternating or growing changes, no order, or an order out of range)
// the finest level itself, with the untrusted GCI band above as its error, never less than the
// last change: levels that move by that much are not known better than that.
struct RichardsonEstimate {
  double value = std::nan("");  // the limit where the order is trusted, else the finest level
  double error = std::nan("");  // ≥ 0, in the levels' units
  double order = std::nan("");  // the observed order, trusted or not (NaN: no order)
  bool trusted = false;
};

inline RichardsonEstimate richardson_estimate(double e1, double e2, double e3, double r) {
  const RichardsonRate rate = richardson_rate(e1, e2, e3, r);
  // NaN orders (q ≤ 0, or 0/0) fail both comparisons and are refused.
  if (rate.order >= kTrustedOrderMin && rate.order <= kTrustedOrderMax)
    return {.value = rate.limit,
            .error = std::abs(rate.finest_error),
            .order = rate.order,
            .trusted = true};
  return {.value = e3, .error = untrusted_band(r) * std::abs(e2 - e3), .order = rate.order};
}

}  // namespace asperity
