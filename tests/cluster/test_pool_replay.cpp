// The task pool on paper (cluster/pool_replay.hpp) and the study's schedule estimate on it
// (study/schedule_estimate.hpp): the hand-out order, the wall time and idle share, and the
// cluster study's costing rules. Costs are small integers, whose sums are exact in double: the
// wall and drain times are asserted exactly.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cluster/pool_replay.hpp"
#include "solver/core/error.hpp"
#include "solver/io/csv.hpp"
#include "study/case_weight.hpp"
#include "study/schedule_estimate.hpp"

namespace asperity {
namespace {

TEST(PoolReplay, FirstFreeWorkerTakesTheNextTask) {
  // 2 workers: 5 on one; 1, 1, 1 on the other, which runs out at 3.
  const cluster::PoolStats s = cluster::replay_pool({5, 1, 1, 1}, 2);
  EXPECT_EQ(s.workers, 2);
  EXPECT_EQ(s.wall_seconds, 5);
  EXPECT_EQ(s.busy_seconds, 8);
  EXPECT_EQ(s.drain_seconds, 2);
  // 1 − 8/10: one rounding in the quotient and one in the difference.
  EXPECT_DOUBLE_EQ(s.idle_fraction, 0.2);
  // Free times [0, 0] -> [0, 3] -> [2, 3] -> [3, 4] -> [4, 4]: both end together.
  const cluster::PoolStats even = cluster::replay_pool({3, 2, 2, 1}, 2);
  EXPECT_EQ(even.wall_seconds, 4);
  EXPECT_EQ(even.idle_fraction, 0);
  EXPECT_EQ(even.drain_seconds, 0);
  EXPECT_THROW(cluster::replay_pool({1}, 0), InputError);
}

io::CsvTable table(const std::vector<std::vector<std::string>>& rows) {
  return {.header = {"particle", "model", "resolution", "element_size_rel", "cpu_seconds"},
          .rows = rows};
}

TEST(ScheduleEstimate, ExpensiveFirstIsTheStudysOrder) {
  // In plan order the 5 s fem case at 2000 triangles comes last and runs alone at the end.
  const io::CsvTable t = table({{"p", "fem", "100", "", "1"},
                                {"p", "sphere", "", "", "1"},
                                {"p", "rigid", "1000", "", "1"},
                                {"p", "fem", "500", "", ""},  // failed: left out
                                {"p", "fem", "2000", "", "5"}});
  const std::vector<study::CostedCase> cases = study::measured_cases(t);
  ASSERT_EQ(cases.size(), 4u);
  // case_weight: fem N^1.4 (2000: 66), rigid half that (1000: 12.6), fem 100: 1, sphere 0.01.
  EXPECT_GT(study::case_weight(cases[3].key), study::case_weight(cases[2].key));
  EXPECT_GT(study::case_weight(cases[2].key), study::case_weight(cases[0].key));
  EXPECT_GT(study::case_weight(cases[0].key), study::case_weight(cases[1].key));
  const study::ScheduleReplay r = study::replay_schedule(cases, 2);
  EXPECT_EQ(r.expensive_first.wall_seconds, 5);  // 5 | 1 + 1 + 1
  EXPECT_EQ(r.expensive_first.drain_seconds, 2);
  EXPECT_EQ(r.plan_order.wall_seconds, 6);  // 1 + 5 | 1 + 1
  EXPECT_EQ(r.plan_order.drain_seconds, 4);
}

TEST(ScheduleEstimate, RefinedCaseWeighsItsEdgeOverH) {
  // At 500 triangles the surface edge is √(29/500) = 0.241 R: h = 0.04 R costs 6.02 coarse cases.
  const study::CaseKey coarse{.model = study::ModelKind::fem, .resolution = 500};
  study::CaseKey refined = coarse;
  refined.level = 2;
  refined.relative_size = 0.04;
  // Two roundings (the square root, the quotient) in the ratio.
  EXPECT_DOUBLE_EQ(study::case_weight(refined) / study::case_weight(coarse),
                   std::sqrt(29.0 / 500) / 0.04);
}

TEST(ScheduleEstimate, ClusterStudyCostsFromTheFullStudy) {
  std::vector<std::vector<std::string>> rows;
  for (const char* p : {"p", "q"}) {
    for (const char* m : {"fem", "rigid", "rigid-penalty"}) {
      for (const char* n : {"100", "250", "500", "1000", "2000"})
        rows.push_back({p, m, n, "", "1"});
    }
    rows.push_back({p, "sphere", "", "", "1"});
    rows.push_back({p, "sphere-local", "", "", "1"});
    for (const char* n : {"1000", "2000"}) {
      rows.push_back({p, "fem", n, "0.08", "1"});
      rows.push_back({p, "fem", n, "0.04", "1"});
    }
  }
  // p's refined levels at 500 grow 3 times from 0.08 to 0.04 R; q's 0.04 R case failed.
  rows.push_back({"p", "fem", "500", "0.08", "2"});
  rows.push_back({"p", "fem", "500", "0.04", "6"});
  rows.push_back({"q", "fem", "500", "0.08", "4"});
  rows.push_back({"q", "fem", "500", "0.04", ""});
  const std::vector<study::CostedCase> cases = study::cluster_study_cases(table(rows));
  // Per particle and placement: 3 models x 5 resolutions, 2 spheres, 5 x 3 refined levels;
  // both placements.
  ASSERT_EQ(cases.size(), 2u * 2u * 32u);
  const auto cost = [&](std::size_t particle, std::size_t placement, std::size_t k) {
    return cases[particle * 64 + placement * 32 + k].cpu_seconds;
  };
  // The refined levels of the first resolution (100 triangles) cost what 500's do: p at
  // 0.08, 0.04 R measured; 0.02 R the growth (3) once more.
  EXPECT_EQ(cost(0, 0, 17), 2);
  EXPECT_EQ(cost(0, 0, 18), 6);
  EXPECT_EQ(cost(0, 0, 19), 18);
  EXPECT_EQ(cost(0, 1, 19), 18);  // the centroid placement costs what the lowest does
  // q: its failed 0.04 R case costs the median of the others (p's 6); growth 1.5 -> at least 2.
  EXPECT_EQ(cost(1, 0, 18), 6);
  EXPECT_EQ(cost(1, 0, 19), 12);
  // A kind no particle measured cannot be costed.
  EXPECT_THROW(study::cluster_study_cases(table({{"p", "fem", "100", "", "1"}})), InputError);
}

}  // namespace
}  // namespace asperity
