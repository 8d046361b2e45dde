// The task pool in a world of one process and the study's shards: every task runs exactly once,
// in the order given, and the shards of a study cover its particles exactly once.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>
#include <vector>

#include <pthread.h>

#include <gtest/gtest.h>

#include "cluster/task_pool.hpp"
#include "solver/core/error.hpp"
#include "study/study_run.hpp"

namespace asperity::cluster {
namespace {

TEST(TaskPool, EveryTaskOnceWithItsReportAtItsIndex) {
  World world;
  const std::vector<int> order = {4, 0, 3, 1};  // task 2 is not asked for
  std::vector<std::atomic<int>> runs(5);
  int reported = 0;
  const std::vector<TaskReport> reports = run_tasks(
      world, 5, order, 3,
      [&](int k) {
        ++runs[static_cast<std::size_t>(k)];
        return TaskReport{.failed = k == 3, .note = "task " + std::to_string(k)};
      },
      [&](const TaskReport&, int running) {
        ++reported;
        EXPECT_GE(running, 0);
        EXPECT_LE(running, 3);  // never more running than workers
      });
  ASSERT_EQ(reports.size(), 5u);
  for (int k : order) {
    EXPECT_EQ(runs[static_cast<std::size_t>(k)], 1) << k;
    EXPECT_EQ(reports[static_cast<std::size_t>(k)].task, k);
    EXPECT_EQ(reports[static_cast<std::size_t>(k)].note, "task " + std::to_string(k));
  }
  EXPECT_EQ(runs[2], 0);
  EXPECT_EQ(reports[2].task, -1);
  EXPECT_TRUE(reports[3].failed);
  EXPECT_EQ(reported, 4);
}

TEST(TaskPool, OneWorkerTakesTheTasksInTheGivenOrder) {
  World world;
  std::vector<int> seen;
  run_tasks(
      world, 4, {2, 3, 0, 1}, 1,
      [&](int k) {
        seen.push_back(k);
        return TaskReport{};
      },
      nullptr);
  EXPECT_EQ(seen, (std::vector<int>{2, 3, 0, 1}));
}

// Longest first: one task of 8 units and eight of 1 on 2 workers end together (8 + 8 units of
// busy time in 8 units of wall: no idle time); the long task last would leave one worker idle
// for 8 units of 16 (idle fraction 1/3). The two orders are told apart at the midpoint, 1/6:
// a fixed 0.1 on 25 ms units failed once in CI (0.112) when the 2-core machine's other test
// process delayed the wake-ups by ~20 ms. Units of 60 ms make such a delay 0.04 of the long
// task, and the midpoint leaves 1/6 of room on either side.
TEST(TaskPool, IdleFractionMeasuresTheEnd) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "needs 2 cores for 2 workers";
  World world;
  const auto unit = std::chrono::milliseconds(60);
  const auto run = [&](int k) {
    std::this_thread::sleep_for(k == 0 ? 8 * unit : unit);
    return TaskReport{};
  };
  PoolStats first, last;
  run_tasks(world, 9, {0, 1, 2, 3, 4, 5, 6, 7, 8}, 2, run, nullptr, &first);
  run_tasks(world, 9, {1, 2, 3, 4, 5, 6, 7, 8, 0}, 2, run, nullptr, &last);
  EXPECT_EQ(first.workers, 2);
  EXPECT_LT(first.idle_fraction, 1.0 / 6.0);
  EXPECT_GT(last.idle_fraction, 1.0 / 6.0);
  EXPECT_LT(last.idle_fraction, 0.5);  // above 1/3 only by the delays; 1/2 would be one worker
  // the long task ran alone for its last 8 units (0.48 s); a delay of a few tens of ms either way
  EXPECT_NEAR(last.drain_seconds, 0.48, 0.1);
}

// Workers are capped at the tasks and the cores (issue 31, class 1: `-j 100000` aborted).
TEST(TaskPool, WorkersAreCappedAtTasksAndCores) {
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  EXPECT_EQ(worker_count(100000, 1000000), cores);
  EXPECT_EQ(worker_count(100000, 1), 1);
  EXPECT_EQ(worker_count(0, 5), 1);
  EXPECT_EQ(worker_count(-3, 5), 1);
  EXPECT_EQ(worker_count(2, 0), 1);
}

// A thread that cannot start ends the starting, not the run: with every new thread's stack set
// beyond any address space, the caller's thread alone does every task once (was std::terminate,
// SIGABRT).
TEST(TaskPool, ThreadsThatCannotStartLeaveTheWorkToTheOthers) {
  pthread_attr_t saved;
  ASSERT_EQ(pthread_getattr_default_np(&saved), 0);
  pthread_attr_t huge;
  pthread_attr_init(&huge);
  ASSERT_EQ(pthread_attr_setstacksize(&huge, std::size_t{1} << 46), 0);  // 64 TiB
  ASSERT_EQ(pthread_setattr_default_np(&huge), 0);
  World world;
  std::vector<std::atomic<int>> runs(9);
  PoolStats stats;
  const std::vector<TaskReport> reports = run_tasks(
      world, 9, {0, 1, 2, 3, 4, 5, 6, 7, 8}, 4,
      [&](int k) {
        ++runs[static_cast<std::size_t>(k)];
        return TaskReport{};
      },
      nullptr, &stats);
  pthread_setattr_default_np(&saved);
  pthread_attr_destroy(&huge);
  pthread_attr_destroy(&saved);
  for (int k = 0; k < 9; ++k) EXPECT_EQ(runs[static_cast<std::size_t>(k)], 1) << k;
  EXPECT_EQ(stats.workers, 1);
}

}  // namespace
}  // namespace asperity::cluster

namespace asperity::study {
namespace {

TEST(Shards, ParseRefusesWhatIsNotKOfN) {
  EXPECT_EQ(parse_shard("2/3").index, 2);
  EXPECT_EQ(parse_shard("2/3").count, 3);
  for (const char* bad : {"3/2", "0/0", "0/2", "1/0", "1", "a/2", "1/2x", "-1/2", "1/-2", ""}) {
    EXPECT_THROW(parse_shard(bad), InputError) << bad;
  }
}

TEST(Shards, CoverEveryParticleOnce) {
  StudyDef def;
  for (int i = 0; i < 7; ++i) def.particles.push_back({.name = "p" + std::to_string(i)});
  for (int n = 1; n <= 9; ++n) {
    std::vector<int> count(7);
    for (int k = 1; k <= n; ++k) {
      for (std::size_t i : shard_particles(def, {.index = k, .count = n})) ++count[i];
    }
    EXPECT_TRUE(std::all_of(count.begin(), count.end(), [](int c) { return c == 1; })) << n;
  }
  EXPECT_EQ(shard_particles(def, {}).size(), 7u);
}

TEST(StudyFolder, FirstDifferenceNamesTheKey) {
  const nlohmann::json a = {{"name", "s"}, {"resolutions", {100, 250}}, {"speed", 2.0}};
  nlohmann::json b = a;
  EXPECT_EQ(first_difference(a, b), "");
  b["resolutions"] = {100, 250, 500};
  EXPECT_EQ(first_difference(a, b), "\"resolutions\" is [100,250] there, [100,250,500] here");
  b = a;
  b["resolutions"][1] = 500;
  EXPECT_EQ(first_difference(a, b), "\"resolutions[1]\" is 250 there, 500 here");
  b = a;
  b.erase("speed");
  EXPECT_EQ(first_difference(a, b), "\"speed\" is 2.0 there, absent here");
}

}  // namespace
}  // namespace asperity::study
