// `asperity run SCENE.json --out DIR`: one scene, the contract's three output files.
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "app/out_folder.hpp"
#include "solver/core/error.hpp"
#include "solver/io/atomic_file.hpp"
#include "solver/io/json_file.hpp"
#include "solver/io/printable.hpp"
#include "solver/run/run_scene.hpp"
#include "solver/scene/scene.hpp"

namespace asperity::app {
namespace {
namespace fs = std::filesystem;

// `asperity run`: its name and its help paragraph.
constexpr CommandText kRun{
    .name = "run",
    .about =
        "Run one scene: writes DIR/summary.json, DIR/force.csv, "
        "DIR/energy.csv (and DIR/vtk/run.pvd with --vtk-every)",
};

struct RunArgs {
  fs::path scene, out;
  bool allow_unsafe_dt = false, quiet = false;
  int vtk_every = 0;  // 0: the scene's output.vtk_every
  bool vtk_ascii = false;
};

int cmd_run(const RunArgs& a) {
  const scene::SceneDef s = scene::load_scene(a.scene);
  check_out_folder(a.out);
  // An earlier run's outputs in the same folder would pass for this run's if it is interrupted
  // or fails: they go before it starts (summary.json, written last, marks a complete run).
  for (const char* f : {"summary.json", "force.csv", "energy.csv"})
    io::remove_earlier_output(a.out / f);
  run::RunOptions options{.dt = std::nullopt,
                          .allow_unsafe_dt = a.allow_unsafe_dt,
                          .keep_rows = true,
                          .progress = !a.quiet};
  if (const int every = a.vtk_every > 0 ? a.vtk_every : s.output.vtk_every; every > 0) {
    options.vtk =
        run::VtkOutput{.dir = a.out / "vtk",
                       .every = every,
                       .encoding = a.vtk_ascii || s.output.vtk_ascii ? io::vtk::Encoding::ascii
                                                                     : io::vtk::Encoding::base64};
  }
  const run::RunResult r = run::run_scene(s, options);
  run::write_outputs(r, a.out);
  const fs::path& out = a.out;
  const bool quiet = a.quiet;
  if (!quiet) {
    // The scene's name and the message (which names bodies) are input: escaped and cut.
    std::cerr << io::printable(s.name, io::kEchoChars) << ": " << r.status
              << (r.message.empty() ? "" : " (" + io::printable(r.message, 300) + ")")
              << ", peak force " << r.summary["peak_force"].get<double>() << " N, "
              << r.summary["steps"].get<long>() << " steps in "
              << r.summary["cpu_seconds"].get<double>() << " s CPU -> " << out.string() << "\n";
    if (r.vtk.frames > 0) {
      std::cerr << "  " << r.vtk.frames << " ParaView frames, " << r.vtk.bytes << " bytes -> "
                << (out / "vtk" / "run.pvd").string() << "\n";
    }
  }
  return r.status == "unstable" ? kExitUnstable : kExitOk;
}

}  // namespace

void add_run_command(CLI::App& app, Action& action) {
  const auto [run, args] = add_command<RunArgs>(app, action, kRun, cmd_run);
  run->add_option("scene", args->scene, "Scene file (JSON, see docs/scenes.md)")->required();
  add_out_folder(*run, args->out);
  run->add_flag("--allow-unsafe-dt", args->allow_unsafe_dt,
                "Run a given dt even above the predicted critical step");
  add_quiet(*run, args->quiet, "No progress or summary line on stderr");
  run->add_option("--vtk-every", args->vtk_every,
                  "ParaView frames every N steps, at the peak force and at the end: "
                  "DIR/vtk/run.pvd (overrides the scene's output.vtk_every)")
      ->check(CLI::PositiveNumber);
  run->add_flag("--vtk-ascii", args->vtk_ascii,
                "Frames in ASCII instead of appended base64 (about 2.3x larger)");
}

}  // namespace asperity::app
