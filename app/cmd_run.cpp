// `asperity run SCENE.json --out DIR`: one scene, the contract's three output files.
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/commands.hpp"
#include "app/out_folder.hpp"
#include "core/error.hpp"
#include "run/run_scene.hpp"
#include "scene/scene.hpp"

namespace asperity::app {
namespace {
namespace fs = std::filesystem;

int cmd_run(const fs::path& scene_file, const fs::path& out, bool allow_unsafe_dt, bool quiet) {
  const scene::SceneDef s = scene::load_scene(scene_file);
  check_out_folder(out);
  // An earlier run's outputs in the same folder would pass for this run's if it is interrupted
  // or fails: they go before it starts (summary.json, written last, marks a complete run).
  for (const char* f : {"summary.json", "force.csv", "energy.csv"}) {
    std::error_code ec;
    fs::remove(out / f, ec);
  }
  const run::RunResult r = run::run_scene(s, {.dt = std::nullopt,
                                              .allow_unsafe_dt = allow_unsafe_dt,
                                              .keep_rows = true,
                                              .progress = !quiet});
  run::write_outputs(r, out);
  if (!quiet) {
    std::cerr << s.name << ": " << r.status << (r.message.empty() ? "" : " (" + r.message + ")")
              << ", peak force " << r.summary["peak_force"].get<double>() << " N, "
              << r.summary["steps"].get<long>() << " steps in "
              << r.summary["cpu_seconds"].get<double>() << " s CPU -> " << out.string() << "\n";
  }
  return r.status == "unstable" ? kExitUnstable : kExitOk;
}

}  // namespace

void add_run_command(CLI::App& app, Action& action) {
  struct Args {
    fs::path scene, out;
    bool allow_unsafe_dt = false, quiet = false;
  };
  auto args = std::make_shared<Args>();
  auto* run = app.add_subcommand(
      "run", "Run one scene: writes DIR/summary.json, DIR/force.csv, DIR/energy.csv");
  run->add_option("scene", args->scene, "Scene file (JSON, see docs/contract.md)")->required();
  run->add_option("--out", args->out, "Output folder")->required();
  run->add_flag("--allow-unsafe-dt", args->allow_unsafe_dt,
                "Run a given dt even above the predicted critical step");
  run->add_flag("-q,--quiet", args->quiet, "No progress or summary line on stderr");
  run->callback([args, &action] {
    action = [args] { return cmd_run(args->scene, args->out, args->allow_unsafe_dt, args->quiet); };
  });
}

}  // namespace asperity::app
