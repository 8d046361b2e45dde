// `asperity study STUDY.json --out DIR`: the particle-geometry sensitivity study (issue 7):
// runs every case not done yet, on this machine's threads or over MPI ranks (docs/cluster.md),
// then writes the study's tables (study/study_tables.hpp).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "app/out_folder.hpp"
#include "cluster/world.hpp"
#include "solver/core/error.hpp"
#include "study/study_def.hpp"
#include "study/study_run.hpp"
#include "study/study_tables.hpp"

namespace asperity::app {
namespace {

// `asperity study`: its name and its help paragraph.
constexpr CommandText kStudy{
    .name = "study",
    .about =
        "Particle-geometry study: particles x resolutions x models (fem, rigid, rigid-penalty, "
        "sphere, sphere-local) x placements, each striking a rigid block, fem also at element "
        "sizes refined at the strike point (the key \"refinement\"). The key \"reference\" names "
        "what every error is measured against: \"finest\" (default), the Richardson limit of the "
        "fem sequence at the finest resolution, with its estimated error; or \"source\", the "
        "particle itself: its source surface kept around the strike point, refined there in 3 "
        "levels (\"reference_elements_across\", 3: the finest level's elements across Hertz's "
        "contact radius; \"reference_patch_check\": also on the doubled patch; a fourth level at "
        "half the finest where the three's peak force shows no steady order and an uncertainty "
        "above 1 %, \"reference_max_levels\": 4), the Richardson limit of the last three. "
        "Resumable (finished cases are kept). Writes DIR/cases/, "
        "DIR/cases.csv, DIR/classification.csv, DIR/guidelines.csv, DIR/answer.csv (what to use "
        "for 2, 5 and 10 %) and DIR/study_summary.json. "
        "Under mpirun or srun the cases are spread over the ranks (docs/cluster.md)",
};

struct StudyArgs {
  std::filesystem::path study, out;
  int jobs = 0;
  double stop_after = 0;  // minutes of wall; 0: none
  std::string shard;
  bool quiet = false, allow_failed = false, collect = false;
};

// `--collect`: the tables from the case folders (after the shards of a job array). Refused while a
// case has neither finished nor failed: tables written then would silently leave it out.
int collect(const study::StudyDef& def, const StudyArgs& args) {
  if (!std::filesystem::exists(args.out / "study.json")) {
    throw InputError(args.out.string() +
                     ": no study.json: not a study folder (run the study, or "
                     "its shards, into it first)");
  }
  std::optional<study::FolderLock> lock;
  lock.emplace(args.out, study::Shard{});
  study::adopt_folder(def, args.out);
  if (const int unfinished = study::unfinished_cases(def, args.out); unfinished > 0) {
    std::fprintf(stderr,
                 "study %s: %d of %zu cases in %s have not run (a shard not run yet, cancelled or "
                 "out of time: run it again, then --collect); no table written\n",
                 def.name.c_str(), unfinished,
                 study::plan_cases(def).size() + study::plan_source_cases(def, args.out).size(),
                 args.out.string().c_str());
    return kExitFailure;
  }
  const study::StudyTables tables = study::write_tables(def, args.out, study::StudyOutcome{});
  if (!args.quiet) {
    std::fprintf(stderr, "study %s: %d cases collected (%d done, %d failed) -> %s\n",
                 def.name.c_str(), tables.cases, tables.done, tables.failed,
                 (args.out / "cases.csv").string().c_str());
  }
  return tables.failed > 0 && !args.allow_failed ? kExitFailure : kExitOk;
}

int run(const StudyArgs& args) {
  if (args.jobs < 0)
    throw InputError("--jobs: must be >= 0 (got " + std::to_string(args.jobs) + ")");
  const study::Shard shard = args.shard.empty() ? study::Shard{} : study::parse_shard(args.shard);
  if (shard.count > 0 && args.collect) throw InputError("--collect: not with --shard");
  const study::StudyDef def = study::load_study(args.study);
  check_out_folder(args.out);
  if (args.collect) {
    if (cluster::launched_ranks() > 1) throw InputError("--collect: run it as one process");
    return collect(def, args);
  }
  if (args.stop_after < 0) throw InputError("--stop-after: must be > 0 minutes");
  const auto stop_at = study::deadline_after(args.stop_after);
  cluster::World world;
  return world.guard([&] {
    const study::StudyOutcome o = study::run_study(def, args.out,
                                                   {.jobs = args.jobs,
                                                    .quiet = args.quiet,
                                                    .shard = shard,
                                                    .world = &world,
                                                    .stop_at = stop_at});
    const int code =
        (o.failed > 0 && !args.allow_failed) || o.postponed > 0 ? kExitFailure : kExitOk;
    if (!world.root()) return code;
    if (o.postponed > 0) {
      // Tables written now would silently leave the postponed cases out (as --collect refuses).
      std::fprintf(stderr,
                   "study %s: stopped after %.1f min (--stop-after): %d of %d cases postponed, "
                   "%d run, %d kept from before, %d failed; run it again to go on; no table "
                   "written\n",
                   def.name.c_str(), args.stop_after, o.postponed, o.cases, o.ran, o.skipped,
                   o.failed);
      return code;
    }
    // A shard's tables would hold only its cases: --collect (or a whole run) writes them.
    if (shard.count == 0) study::write_tables(def, args.out, o);
    if (!args.quiet) {
      std::fprintf(stderr,
                   "study %s%s: %d cases (%d run, %d kept from before, %d failed) in %.1f s wall, "
                   "%.1f s CPU; %d ranks, %d workers, %.1f %% idle, %.1f s at the end with idle "
                   "workers -> %s\n",
                   def.name.c_str(), shard.count > 0 ? (" shard " + args.shard).c_str() : "",
                   o.cases, o.ran, o.skipped, o.failed, o.wall_seconds, o.cpu_seconds, o.ranks,
                   o.workers, 100 * o.idle_fraction, o.drain_seconds,
                   shard.count > 0 ? "its cases in DIR/cases; --collect writes the tables"
                                   : (args.out / "cases.csv").string().c_str());
    }
    return code;
  });
}

}  // namespace

void add_study_command(CLI::App& app, Action& action) {
  const auto [cmd, args] = add_command<StudyArgs>(app, action, kStudy, run);
  cmd->add_option("study", args->study, "Study file (JSON, e.g. data/study/default.json)")
      ->required();
  add_out_folder(*cmd, args->out);
  add_jobs(*cmd, args->jobs,
           "Worker threads per process (default: the study's \"jobs\", else every core)");
  cmd->add_option("--shard", args->shard,
                  "K/N: only the K-th of N shards (every N-th particle from the K-th: its meshes "
                  "and cases; no tables); shards may run side by side into one folder");
  cmd->add_option("--stop-after", args->stop_after,
                  "Wall minutes: no case starts after them and a running case stops within 256 "
                  "steps; what is cut is postponed (not failed, nothing written as done), no "
                  "table is written and the exit status is 1; the next run goes on (e.g. a "
                  "batch job's time limit, docs/cluster.md)");
  cmd->add_flag("--collect", args->collect,
                "Run nothing: write the tables from the cases in DIR (after the shards)");
  add_quiet(*cmd, args->quiet, "Only errors on stderr");
  cmd->add_flag(
      "--allow-failed", args->allow_failed,
      "Exit 0 even when a case failed (the report target: its report lists the failures)");
}

}  // namespace asperity::app
