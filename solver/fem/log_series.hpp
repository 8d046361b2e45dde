// The natural logarithm as plain arithmetic (no library call, no table, no branch), so that the
// batched element loop (fem/internal_forces.cpp) can take the ln J of a whole batch in vector
// registers instead of one libm call per element (a tenth of the batched element work was that
// call; docs/physics.md, "FEM/DEM step cost").
//
// Method (the classical argument reduction and atanh series, e.g. J.-M. Muller, "Elementary
// Functions: Algorithms and Implementation"): write
// x = 2^k (1 + f) with 1 + f in [√½, √2), so |f| ≤ 0.4143; then with s = f/(2 + f),
//   ln(1 + f) = 2 atanh s = 2s + 2s³/3 + 2s⁵/5 + …,   |s| ≤ 0.1716, z = s² ≤ 0.02944,
// rearranged as ln(1 + f) = f − f²/2 + s (f²/2 + R), R = Σ_{j≥1} 2 z^j/(2j + 1) (2s = f − s f,
// and s f = f²/2 − s f²/2), so the leading term f is exact and the rest a small correction.
// The series is summed to j = 10: the first term left out, 2 z¹¹/23 relative to 2s, is below
// 1e-18, far under the 2⁻⁵³ of a double; the Taylor coefficients 2/(2j + 1) need no fitting.
// k ln 2 is added in two parts (ln 2 = hi + lo, hi with 32 significant bits) so that k·hi is
// exact. Within 1 ulp of the correctly rounded ln x on the tests' sweep (tests/fem/
// test_log_series.cpp); not the same bits as libm's log everywhere, so a change to it moves
// results at the level of round-off.
//
// The exponent and mantissa are split by integer operations on the bits that AVX2 has for 64-bit
// lanes (add, logical shift, and, or; no 64-bit arithmetic shift or integer → double
// conversion): k + 1023 is put in the low bits of 2⁵² and 2⁵² subtracted, which is exact.
//
// Valid for normal positive finite x (DBL_MIN ≤ x < ∞); the caller handles the rest (J ≤ 0 is an
// inverted element, internal_forces.cpp) and takes std::log for subnormal or infinite x.
#pragma once

#include <bit>
#include <cstdint>

namespace asperity::fem {

inline double log_series(double x) {
  // √½'s bits: adding 1.0's bits minus these moves [√½, √2) mantissas into one binade, so the
  // exponent field is k + 1023 with 1 + f in [√½, √2).
  constexpr std::uint64_t kSqrtHalf = 0x3fe6a09e667f3bcdULL;
  constexpr std::uint64_t kOne = 0x3ff0000000000000ULL;
  constexpr std::uint64_t kMantissa = 0x000fffffffffffffULL;
  constexpr std::uint64_t kTwo52 = 0x4330000000000000ULL;  // 2⁵² as a double
  const std::uint64_t u = std::bit_cast<std::uint64_t>(x) + (kOne - kSqrtHalf);
  const std::uint64_t biased = u >> 52;  // k + 1023
  const double k = std::bit_cast<double>(kTwo52 | biased) - (4503599627370496.0 + 1023.0);
  const double f = std::bit_cast<double>((u & kMantissa) + kSqrtHalf) - 1.0;
  // ln 2 = kLn2Hi + kLn2Lo; kLn2Hi has its low 21 bits zero, so k·kLn2Hi is exact for |k| < 2¹¹.
  constexpr double kLn2Hi = 6.93147180369123816490e-01;  // 0x3fe62e42fee00000
  constexpr double kLn2Lo = 1.90821492927058770002e-10;  // ln 2 − kLn2Hi
  const double s = f / (2.0 + f);
  const double z = s * s;
  const double r =
      z * (2.0 / 3 +
           z * (2.0 / 5 +
                z * (2.0 / 7 +
                     z * (2.0 / 9 +
                          z * (2.0 / 11 +
                               z * (2.0 / 13 +
                                    z * (2.0 / 15 +
                                         z * (2.0 / 17 + z * (2.0 / 19 + z * (2.0 / 21))))))))));
  const double hfsq = 0.5 * f * f;
  return k * kLn2Hi - ((hfsq - (s * (hfsq + r) + k * kLn2Lo)) - f);
}

}  // namespace asperity::fem
