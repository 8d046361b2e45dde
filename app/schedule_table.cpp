// schedule_table CASES.csv MODE WORKERS OUT.json: a study's wall time and idle share on W workers
// from its measured per-case CPU seconds (study/schedule_estimate.hpp: the task pool replayed in
// the study's hand-out order and in its plan order), for tools/report/schedule_estimate.py, which
// only formats it (docs/cluster.md and docs/study.md quote it).
//
// CASES.csv: plain fields with the columns particle, model, resolution, element_size_rel and
// cpu_seconds (a study's cases.csv, those columns; empty cpu_seconds: a failed case). MODE:
// "measured" (the table's own cases) or "cluster-study" (data/study/cluster.json's cases costed
// from a full study's, study::cluster_study_cases). WORKERS: worker counts, comma-separated.
// Writes OUT.json: "cases", "cpu_seconds" (Σ in plan order), "longest" (s), and "replays", one
// per worker count: {"workers", "expensive_first": {...}, "plan_order": {...}}, each with
// "wall_seconds", "idle_fraction" and "drain_seconds" (cluster/task_pool.hpp's PoolStats). Numbers
// in the shortest form that reads back to the same double. Bad input: one line naming the file
// and the problem, exit 2.
#include <algorithm>
#include <charconv>
#include <string>
#include <vector>

#include "cluster/task_pool.hpp"
#include "solver/core/error.hpp"
#include "solver/io/atomic_file.hpp"
#include "solver/io/csv.hpp"
#include "solver/io/json_file.hpp"
#include "study/schedule_estimate.hpp"

namespace {

using asperity::io::Json;

// WORKERS: whole numbers ≥ 1, comma-separated.
std::vector<int> worker_counts(const std::string& text) {
  std::vector<int> out;
  for (const std::string& w : asperity::io::csv_split(text)) {
    int n = 0;
    const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), n);
    if (w.empty() || ec != std::errc() || end != w.data() + w.size() || n < 1)
      throw asperity::InputError("WORKERS: \"" + w + "\" is not a worker count (1 or more)");
    out.push_back(n);
  }
  if (out.empty()) throw asperity::InputError("WORKERS: no worker count");
  return out;
}

Json pool_json(const asperity::cluster::PoolStats& s) {
  return {{"wall_seconds", s.wall_seconds},
          {"idle_fraction", s.idle_fraction},
          {"drain_seconds", s.drain_seconds}};
}

}  // namespace

int main(int argc, char** argv) {
  return asperity::io::table_program(
      argc, argv, 4, "schedule_table CASES.csv measured|cluster-study WORKERS OUT.json", [&] {
        namespace study = asperity::study;
        const asperity::io::CsvTable t = asperity::io::read_csv_table(argv[1]);
        const std::string mode = argv[2];
        if (mode != "measured" && mode != "cluster-study")
          throw asperity::InputError("MODE must be \"measured\" or \"cluster-study\"");
        const std::vector<int> workers = worker_counts(argv[3]);
        const std::vector<study::CostedCase> cases =
            mode == "measured" ? study::measured_cases(t) : study::cluster_study_cases(t);
        if (cases.empty()) throw asperity::InputError("no case with a measured cpu_seconds");
        double total = 0, longest = 0;
        for (const study::CostedCase& c : cases) {
          total += c.cpu_seconds;
          longest = std::max(longest, c.cpu_seconds);
        }
        Json replays = Json::array();
        for (int w : workers) {
          const study::ScheduleReplay r = study::replay_schedule(cases, w);
          replays.push_back({{"workers", w},
                             {"expensive_first", pool_json(r.expensive_first)},
                             {"plan_order", pool_json(r.plan_order)}});
        }
        const Json out = {{"cases", cases.size()},
                          {"cpu_seconds", total},
                          {"longest", longest},
                          {"replays", replays}};
        asperity::io::write_atomically(argv[4], out.dump(1) + "\n");
      });
}
