// `asperity study STUDY.json --out DIR`: the particle-geometry sensitivity study (issue 7):
// runs every case not done yet, then writes the study's tables (study/study_tables.hpp).
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/cli_numbers.hpp"
#include "app/commands.hpp"
#include "app/out_folder.hpp"
#include "core/error.hpp"
#include "study/study_def.hpp"
#include "study/study_run.hpp"
#include "study/study_tables.hpp"

namespace asperity::app {

void add_study_command(CLI::App& app, Action& action) {
  struct Args {
    std::filesystem::path study, out;
    int jobs = 0;
    bool quiet = false, allow_failed = false;
  };
  auto args = std::make_shared<Args>();
  auto* cmd =
      app.add_subcommand("study",
                         "Particle-geometry study: particles x resolutions x models (fem, rigid, "
                         "sphere) x placements, "
                         "each striking a block; resumable (finished cases are kept). Writes "
                         "DIR/cases/, DIR/cases.csv, "
                         "DIR/classification.csv, DIR/guidelines.csv and DIR/study_summary.json");
  cmd->add_option("study", args->study, "Study file (JSON, e.g. data/study/default.json)")
      ->required();
  cmd->add_option("--out", args->out, "Output folder")->required();
  cmd->add_option("-j,--jobs", args->jobs,
                  "Worker threads (default: the study's \"jobs\", else every core)")
      ->check(whole_number(0, 4096));
  cmd->add_flag("-q,--quiet", args->quiet, "Only errors on stderr");
  cmd->add_flag(
      "--allow-failed", args->allow_failed,
      "Exit 0 even when a case failed (the report target: its report lists the failures)");
  cmd->callback([args, &action] {
    action = [args] {
      if (args->jobs < 0)
        throw InputError("--jobs: must be >= 0 (got " + std::to_string(args->jobs) + ")");
      const study::StudyDef def = study::load_study(args->study);
      check_out_folder(args->out);
      const study::StudyOutcome o =
          study::run_study(def, args->out, {.jobs = args->jobs, .quiet = args->quiet});
      const study::StudyTables tables = study::write_tables(def, args->out, o);
      if (!args->quiet) {
        std::fprintf(stderr,
                     "study %s: %d cases (%d run, %d kept from before, %d failed) in %.1f s wall, "
                     "%.1f s CPU "
                     "-> %s\n",
                     def.name.c_str(), o.cases, o.ran, o.skipped, o.failed, o.wall_seconds,
                     o.cpu_seconds, (args->out / "cases.csv").string().c_str());
      }
      (void)tables;
      return o.failed > 0 && !args->allow_failed ? kExitFailure : kExitOk;
    };
  });
}

}  // namespace asperity::app
