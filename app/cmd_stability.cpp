// `asperity stability SCENE.json --out DIR [--factors ...]`: the time-step stability sweep.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "app/cli_numbers.hpp"
#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "app/out_folder.hpp"
#include "solver/core/error.hpp"
#include "solver/run/stability_sweep.hpp"
#include "solver/scene/scene.hpp"

namespace asperity::app {

namespace {

// `asperity stability`: its name and its help paragraph.
constexpr CommandText kStability{
    .name = "stability",
    .about =
        "Sweep the time step as multiples of the predicted critical step: writes DIR/stability.csv "
        "and DIR/summary.json (dt_critical_predicted, dt_stable_max_measured)",
};

struct StabilityArgs {
  std::filesystem::path scene, out;
  std::string factors;
  CLI::Option* factors_option = nullptr;
  double reference_factor = 0;
  bool quiet = false;
};

int sweep(const StabilityArgs& a) {
  // Validate everything before running anything.
  const std::vector<double> factors = a.factors_option->count() == 0
                                          ? run::default_stability_factors()
                                          : run::parse_factors(a.factors, "--factors");
  const scene::SceneDef s = scene::load_scene(a.scene);
  check_out_folder(a.out);
  const auto progress = [&](const run::StabilityRow& r, int k, int n) {
    if (!a.quiet) {
      std::fprintf(
          stderr,
          "[%d/%d] factor %-6g dt %-12.4g %-10s drift %.3g  peak error %+.2e  (%.2f s CPU)\n", k, n,
          r.factor, r.dt, r.status.c_str(), r.energy_drift, r.peak_force_error, r.cpu_seconds);
    }
  };
  const run::StabilityResult result = run::stability_sweep(
      s, factors, a.reference_factor > 0 ? std::optional<double>(a.reference_factor) : std::nullopt,
      progress);
  run::write_stability(result, a.out);
  if (!a.quiet) {
    std::fprintf(stderr, "predicted %.4g s, measured stable up to %s -> %s\n",
                 result.summary["dt_critical_predicted"].get<double>(),
                 result.summary["dt_stable_max_measured"].dump().c_str(),
                 (a.out / "stability.csv").string().c_str());
  }
  return kExitOk;
}

}  // namespace

void add_stability_command(CLI::App& app, Action& action) {
  const auto [cmd, args] = add_command<StabilityArgs>(app, action, kStability, sweep);
  cmd->add_option("scene", args->scene, "Scene file (JSON)")->required();
  add_out_folder(*cmd, args->out);
  args->factors_option =
      cmd->add_option("--factors", args->factors,
                      "Comma-separated multiples of the predicted critical step "
                      "(default 0.05,0.1,0.25,0.5,0.75,0.9,1,1.1,1.25,1.5,2,3,5)");
  cmd->add_option(
         "--reference-factor", args->reference_factor,
         "Factor of the converged reference run for the accuracy columns (default: the "
         "smaller of the automatic step's dt_safety and an eighth of the smallest factor); at most "
         "1, the predicted critical step: a reference beyond it may be unstable")
      ->check(real_number(0, 1, true));
  add_quiet(*cmd, args->quiet, "Only errors on stderr");
}

}  // namespace asperity::app
