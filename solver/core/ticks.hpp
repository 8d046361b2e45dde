// A cheap monotonic tick counter for per-phase profiles: the time-stamp counter on x86-64
// (a few ns a read, against ~30 ns for steady_clock), steady_clock nanoseconds elsewhere. Ticks
// become seconds by the ratio of a run's wall time to its tick count (ticks_to_seconds).
#pragma once

#include <chrono>
#include <cstdint>

#if defined(__x86_64__) || defined(_M_X64)
#include <x86intrin.h>
#endif

namespace asperity {

inline std::uint64_t ticks() {
#if defined(__x86_64__) || defined(_M_X64)
  return __rdtsc();
#else
  return static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
#endif
}

// Seconds per tick, measured over an interval whose wall time and tick count are both known.
inline double seconds_per_tick(double wall_seconds, std::uint64_t tick_count) {
  return tick_count > 0 ? wall_seconds / static_cast<double>(tick_count) : 0.0;
}

}  // namespace asperity
