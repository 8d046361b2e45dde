// A small, fully specified random number generator, so that a seed gives the same particle with
// every compiler and standard library (std::uniform_*_distribution differs between libraries).
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

#include "solver/core/vec.hpp"

namespace asperity::geometry {

// SplitMix64 (Steele, Lea & Flood 2014, "Fast splittable pseudorandom number generators";
// constants as in Vigna's reference implementation).
struct SplitMix64 {
  std::uint64_t state;

  std::uint64_t next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  // Uniform in [0, 1): the top 53 bits, exactly representable.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Uniform on the unit sphere (Archimedes: z uniform in [−1, 1], azimuth uniform).
  Vec3 unit_vector() {
    const double z = uniform(-1.0, 1.0), phi = uniform(0.0, 2.0 * std::numbers::pi);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
  }
};

}  // namespace asperity::geometry
