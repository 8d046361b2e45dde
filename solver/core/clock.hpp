// The CPU clocks runs and studies report: the process's (a run, one thread) and the calling
// thread's (a study case on a pool thread, where the process clock would add the other threads').
#pragma once

#include <ctime>

namespace asperity {

inline double cpu_seconds() {
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

inline double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace asperity
