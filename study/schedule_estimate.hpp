// A study's wall time and idle share on W workers, from its measured per-case CPU seconds: the
// task pool (cluster/pool_replay.hpp) replayed in the order `asperity study` hands the cases out
// (case_weight: the most expensive first) and, for comparison, in the study's plan order; each
// case takes its measured cpu_seconds (meshing and messages left out). docs/cluster.md and
// docs/study.md quote it through tools/report/schedule_estimate.py (app/schedule_table).
#pragma once

#include <string>
#include <vector>

#include "cluster/task_pool.hpp"
#include "solver/io/csv.hpp"
#include "study/study_run.hpp"

namespace asperity::study {

// One case of the replay: what case_weight reads of it, and its cost (s).
struct CostedCase {
  CaseKey key;
  double cpu_seconds = 0;
};

// The costed rows of a cases table with the columns particle, model, resolution,
// element_size_rel and cpu_seconds (a study's cases.csv, those columns; more are ignored), in the
// table's order; a row with no cpu_seconds (a failed case) is left out.
std::vector<CostedCase> measured_cases(const io::CsvTable& cases);

// The cases of data/study/cluster.json (every particle of the table, both placements; fem, rigid
// and rigid-penalty at 100, 250, 500, 1000 and 2000 triangles, the two spheres, and fem refined to
// h = 0.08, 0.04 and 0.02 R at every resolution), in plan order, each costed from the full study's
// measured cases (reports/study-full/cases.csv: lowest placement, refined at 500, 1000 and 2000
// triangles):
//  - the centroid placement costs what the lowest does (same meshes, same steps);
//  - a refined level at 100 or 250 triangles costs what it does at 500 (the refined element size,
//    not the surface, sets its elements and step: docs/study.md, "The full study");
//  - h = 0.02 R costs what 0.04 R does times the measured growth from 0.08 to 0.04 R, at least 2
//    (each halving of h halves the step, and the growth measured so far repeats);
//  - a case that failed in the full study (no CPU) costs the median (solver/core/quantile.hpp) of
//    the others at its model, resolution and level.
std::vector<CostedCase> cluster_study_cases(const io::CsvTable& full_study);

// The pool on `workers` workers, the cases handed out most expensive first (case_weight; equal
// weights in plan order, as the study's stable sort) and in plan order.
struct ScheduleReplay {
  cluster::PoolStats expensive_first, plan_order;
};
ScheduleReplay replay_schedule(const std::vector<CostedCase>& cases, int workers);

}  // namespace asperity::study
