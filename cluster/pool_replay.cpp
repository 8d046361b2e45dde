// The pool on paper (pool_replay.hpp): a min-heap of the workers' free times.
#include "cluster/pool_replay.hpp"

#include <algorithm>
#include <functional>
#include <queue>

#include "solver/core/error.hpp"

namespace asperity::cluster {

PoolStats replay_pool(const std::vector<double>& costs, int workers) {
  if (workers < 1) throw InputError("a pool needs at least one worker");
  std::priority_queue<double, std::vector<double>, std::greater<>> free(
      std::greater<>(), std::vector<double>(static_cast<std::size_t>(workers), 0.0));
  double busy = 0;
  for (double c : costs) {
    // The first free worker takes the next task.
    const double start = free.top();
    free.pop();
    free.push(start + c);
    busy += c;
  }
  // The heap's top is the first worker to run out of tasks; its last is the wall time.
  const double first_idle = free.top();
  double wall = first_idle;
  for (; !free.empty(); free.pop()) wall = std::max(wall, free.top());
  return {.workers = workers,
          .wall_seconds = wall,
          .busy_seconds = busy,
          .idle_fraction = 1 - busy / (workers * wall),
          .drain_seconds = wall - first_idle};
}

}  // namespace asperity::cluster
