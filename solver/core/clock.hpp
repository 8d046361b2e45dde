// The CPU clocks runs and studies report: the process's (a run, one thread) and the calling
// thread's (a study case on a pool thread, where the process clock would add the other threads'),
// the latter also with the child processes the thread waited for (TetGen's).
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

// User + system CPU of the child processes the calling thread has waited for, summed over the
// thread's life, s. TetGen meshes in a forked child (geometry::run_tetgen_isolated), whose CPU is
// in none of its parent's clocks; the thread that waits for it adds that one child's (wait4's
// usage) here. Per thread, because each study worker waits for its own children, where
// getrusage(RUSAGE_CHILDREN) would sum every thread's.
namespace detail {
inline thread_local double waited_children_cpu = 0;
}

inline void add_waited_child_cpu(double seconds) {
  detail::waited_children_cpu += seconds;
}

inline double waited_children_cpu_seconds() {
  return detail::waited_children_cpu;
}

// The calling thread's CPU with its waited-for children's: what a task on one thread cost, its
// TetGen runs included (a study's case or mesh, a pool task).
inline double thread_and_children_cpu_seconds() {
  return thread_cpu_seconds() + waited_children_cpu_seconds();
}

}  // namespace asperity
