// The task pool replayed on paper: tasks of known cost handed out one at a time, in a given order,
// to whichever of W workers is free first (what run_tasks does with real tasks, task_pool.hpp), so
// that the wall time and idle share of a job can be read off its measured costs on any number of
// workers (docs/cluster.md: the default study on 2 to 64 workers, the cluster study on 16 nodes).
// Hand-out, messages and meshing cost nothing here: the replay is the pool's own bound.
#pragma once

#include <vector>

#include "cluster/task_pool.hpp"

namespace asperity::cluster {

// `costs` (s, each ≥ 0) in the order they are handed out, on `workers` (≥ 1) workers all free at
// 0. Returns the pool's statistics as run_tasks reports them: wall_seconds the last worker's end,
// busy_seconds Σ costs, idle_fraction = 1 − Σ costs / (workers × wall), drain_seconds from the
// first worker left without a task to the end.
PoolStats replay_pool(const std::vector<double>& costs, int workers);

}  // namespace asperity::cluster
