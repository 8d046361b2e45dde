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

}  // namespace asperity
