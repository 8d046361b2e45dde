// `asperity advise MESH --tolerance 5% --out DIR`: a user's own particle at K orientations, each
// against its own reference, and the cheapest model, resolution and element size within the
// tolerance (study/advise.hpp, docs/study.md "Advice on a particle").
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "app/cli_numbers.hpp"
#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "app/out_folder.hpp"
#include "solver/core/error.hpp"
#include "solver/geometry/mesh_pipeline.hpp"
#include "study/advise.hpp"
#include "study/recommend.hpp"
#include "study/study_run.hpp"
#include "study/study_tables.hpp"
#include "study/tables/study_cases.hpp"

namespace asperity::app {
namespace {
namespace fs = std::filesystem;

// The least CPU one reference has cost: the source reference's three levels on the contact-local
// surface, 110.6 s (ballast_01, a/1.5 to a/6, with the FEM kernel's AVX2/AVX-512 clones) to 701 s
// (rock_04) per particle and orientation on the 2-core machine, 6 December 2026 (docs/study.md,
// "The source reference"): a budget below it cannot finish one orientation.
constexpr double kReferenceCpuMin = 110.0;

// `asperity advise`: its name and its help paragraph.
constexpr CommandText kAdvise{
    .name = "advise",
    .about =
        "Advice on one particle: its mesh studied at K random orientations (fem, rigid, sphere, "
        "sphere-local at 100-2000 triangles, fem refined at the strike point), each against its "
        "own reference; the cheapest model, resolution and element size within the tolerance at "
        "every orientation, with its error (median, worst), the reference's uncertainty and the "
        "CPU per impact, and the same for 2, 5 and 10 % on every metric. Resumable; writes "
        "DIR/advice.json, DIR/advice.md and the study's folder (docs/study.md)",
};

struct AdviseArgs {
  fs::path mesh, out;
  std::string tolerance = "5%", metric = "peak_force";
  double scale = 1, budget = 0;
  int orientations = 4, jobs = 0;
  bool quiet = false;
};

int advise_particle(const AdviseArgs& args) {
  study::AdviseOptions o{.mesh = args.mesh,
                         .scale = args.scale,
                         .orientations = args.orientations,
                         .metric = args.metric,
                         .tolerance = study::parse_tolerance(args.tolerance, "--tolerance")};
  if (!(args.scale > 0)) throw InputError("--scale: must be > 0");
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const int workers = args.jobs > 0 ? args.jobs : static_cast<int>(cores);
  if (args.budget < 0) throw InputError("--budget: must be > 0 minutes");
  if (args.budget > 0 && args.budget * 60 * workers < kReferenceCpuMin) {
    throw InputError("--budget: " + std::to_string(args.budget) +
                     " min is too little for one reference (at least " +
                     std::to_string(static_cast<int>(kReferenceCpuMin)) + " s of CPU on " +
                     std::to_string(workers) + " workers)");
  }
  check_out_folder(args.out);
  // The mesh checked as the study will read it, before anything is written.
  {
    geometry::PipelineOptions p;
    p.read.scale = args.scale;
    p.tetrahedralize = false;
    geometry::prepare_particle(args.mesh, p);
  }
  const study::StudyDef def = study::write_advice_study(ASPERITY_ADVISE_TEMPLATE, o, args.out);
  // Each orientation is one particle of the study, run as its own shard: orientations finish one
  // after another, so a budget stops between them with whole references.
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  // The budget is also a deadline inside an orientation: the first one, or a sharp corner whose
  // reference costs more than the slowest so far, stops at it (its finished levels are kept and
  // the next run resumes them) instead of running on unbounded.
  const auto stop_at = study::deadline_after(args.budget);
  study::StudyOutcome total;
  int done = 0;
  double slowest = 0;
  bool stopped = false;
  for (int k = 1; k <= args.orientations; ++k) {
    if (args.budget > 0 && elapsed() + slowest > args.budget * 60) break;
    const double before = elapsed();
    const study::StudyOutcome r = study::run_study(def, args.out,
                                                   {.jobs = args.jobs,
                                                    .quiet = args.quiet,
                                                    .shard = {k, args.orientations},
                                                    .stop_at = stop_at});
    slowest = std::max(slowest, elapsed() - before);
    total.cases += r.cases;
    total.ran += r.ran;
    total.skipped += r.skipped;
    total.failed += r.failed;
    total.postponed += r.postponed;
    total.cpu_seconds += r.cpu_seconds;
    if (r.postponed > 0) {
      stopped = true;
      if (!args.quiet) {
        std::fprintf(stderr,
                     "advise %s: orientation %d of %d stopped by --budget (%d of its %d cases "
                     "postponed; a rerun into %s goes on)\n",
                     args.mesh.filename().string().c_str(), k, args.orientations, r.postponed,
                     r.cases, args.out.string().c_str());
      }
      break;
    }
    ++done;
    if (!args.quiet) {
      std::fprintf(stderr, "advise %s: orientation %d of %d done (%.0f s wall so far)\n",
                   args.mesh.filename().string().c_str(), k, args.orientations, elapsed());
    }
  }
  total.wall_seconds = elapsed();
  study::write_tables(def, args.out, total);
  const study::tables::StudyCases cases = study::tables::load_study_cases(def, args.out);
  const nlohmann::ordered_json run_facts = {{"orientations_asked", args.orientations},
                                            {"orientations_run", done},
                                            {"stopped_by_budget", stopped},
                                            {"cases_postponed", total.postponed},
                                            {"cases_failed", total.failed},
                                            {"cpu_seconds", total.cpu_seconds},
                                            {"wall_seconds", total.wall_seconds},
                                            {"budget_minutes", args.budget}};
  const nlohmann::ordered_json advice = study::write_advice(cases, o, run_facts, args.out);
  if (!args.quiet) {
    std::fprintf(stderr, "advise %s -> %s, %s\n", args.mesh.filename().string().c_str(),
                 (args.out / "advice.md").string().c_str(),
                 (args.out / "advice.json").string().c_str());
  }
  return advice["advice"]["model"].is_null() ? kExitFailure : kExitOk;
}

}  // namespace

void add_advise_command(CLI::App& app, Action& action) {
  const auto [cmd, args] = add_command<AdviseArgs>(app, action, kAdvise, advise_particle);
  cmd->add_option("mesh", args->mesh, "The particle's surface (STL, OBJ, PLY, OFF)")->required();
  add_tolerance(*cmd, args->tolerance);
  cmd->add_option("--metric", args->metric, "peak_force, impulse or contact_duration")
      ->check(CLI::IsMember({"peak_force", "impulse", "contact_duration"}))
      ->capture_default_str();
  cmd->add_option("--orientations", args->orientations, "Random orientations (each a reference)")
      ->check(whole_number(1, 64))
      ->capture_default_str();
  cmd->add_option("--budget", args->budget,
                  "Wall minutes: no orientation starts once the slowest so far would end past "
                  "it, and one running at the budget stops there (its finished cases are kept; "
                  "a rerun goes on); the advice comes from the orientations finished (default: "
                  "none)");
  cmd->add_option("--scale", args->scale, "Multiplies the file's coordinates (0.001: mm)")
      ->capture_default_str();
  add_out_folder(*cmd, args->out);
  add_jobs(*cmd, args->jobs, "Worker threads (default: every core)");
  add_quiet(*cmd, args->quiet, "Only errors on stderr");
}

}  // namespace asperity::app
