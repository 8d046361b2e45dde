// Tasks handed out one at a time, in a given order, to the threads of every rank: dynamic load
// balancing for jobs whose tasks differ in cost by 1000× (a 2000-triangle fem case against a
// sphere case). Give the expensive tasks first and the last to finish is a cheap one.
//
// Rank 0 hands out the tasks (a coordinator in its main thread, beside its own workers) and
// receives every task's report as it finishes (for progress); at the end every rank gets every
// report. A task's outputs are files its worker writes: on a cluster the output folder must be
// on a file system every node shares.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "cluster/world.hpp"

namespace asperity::cluster {

// What a task leaves besides its files; `payload` is the task's own text (e.g. a check as JSON).
struct TaskReport {
  int task = -1;
  int rank = 0;
  bool failed = false, skipped = false;  // skipped: done by an earlier run, kept
  // postponed: not run, or stopped unfinished, because the caller's deadline passed
  // (StudyRunOptions::stop_at): nothing written as done, left for the next run.
  bool postponed = false;
  double cpu_seconds = 0;   // the worker's CPU on it, its TetGen children's in
  double busy_seconds = 0;  // wall time the worker spent on it
  std::string note;         // one line for the progress display
  std::string payload;
};

// How well the tasks filled the workers: idle_fraction = 1 − Σ busy / (workers × wall), wall
// from the first task handed out to the last report; drain_seconds: from the first worker that
// found no task left to the last report (the end of the study that runs less than full).
struct PoolStats {
  int workers = 0;
  double wall_seconds = 0, busy_seconds = 0, idle_fraction = 0, drain_seconds = 0;
};

// The workers a rank runs for `threads` asked: at least 1, at most the tasks and the cores (a
// thread beyond either only waits, and each reserves its stack: `-j 100000` asked for 800 GB).
int worker_count(int threads, int tasks);

// Runs tasks order[0], order[1], ... (each an index below `tasks`) on worker_count(threads, tasks)
// workers per rank (fewer when the system cannot start more threads: then as many as it could);
// `run` must not throw. `on_report` (rank 0 only, one call at a time) sees each report as it
// arrives with the count still running. Returns the reports indexed by task (tasks not in
// `order` keep task = -1), on every rank.
std::vector<TaskReport> run_tasks(World& world, int tasks, const std::vector<int>& order,
                                  int threads, const std::function<TaskReport(int)>& run,
                                  const std::function<void(const TaskReport&, int)>& on_report,
                                  PoolStats* stats = nullptr);

}  // namespace asperity::cluster
