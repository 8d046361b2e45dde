// `asperity recommend SCENE --tolerance 5%`: the cheapest model and resolution a study's
// guidelines give for the scene's particle (study/recommend.hpp). JSON on stdout, a line on stderr.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "solver/core/error.hpp"
#include "study/recommend.hpp"

namespace asperity::app {

namespace {

// `asperity recommend`: its name and its help paragraph.
constexpr CommandText kRecommend{
    .name = "recommend",
    .about =
        "Cheapest particle model and resolution within a tolerance on peak force / impulse, from a "
        "study's "
        "guidelines (--study DIR, default data/study/guidelines.json); JSON on stdout",
};

struct RecommendArgs {
  std::filesystem::path scene, study;
  std::string tolerance = "5%", metric = "peak_force+impulse", statistic = "p90", placement;
  bool quiet = false;
};

int recommend_for(const RecommendArgs& a) {
  const study::RecommendOptions o{.tolerance = study::parse_tolerance(a.tolerance, "--tolerance"),
                                  .metric = a.metric,
                                  .statistic = a.statistic,
                                  .placement = a.placement};
  const std::filesystem::path g = a.study.empty()
                                      ? std::filesystem::path(ASPERITY_DEFAULT_GUIDELINES)
                                      : a.study / "guidelines.json";
  if (!std::filesystem::exists(g))
    throw InputError(g.string() + ": no guidelines (run asperity study first)");
  const nlohmann::ordered_json r = study::recommend(a.scene, g, o);
  std::cout << r.dump(1) << "\n";
  if (!a.quiet) {
    const auto& rec = r["recommendation"];
    // The reference's uncertainty beside the answer: the error is known no better.
    const auto& u = rec["reference_uncertainty"];
    const std::string unc =
        u.is_number()
            ? ", reference uncertain by " + std::to_string(u.get<double>() * 100).substr(0, 4) + "%"
            : "";
    std::fprintf(stderr, "%s: %s%s within %s on %s (%s over the study's particles%s)\n",
                 a.scene.string().c_str(), rec["model"].get<std::string>().c_str(),
                 rec["resolution"].is_null()
                     ? ""
                     : (" at " + rec["resolution"].dump() + " triangles").c_str(),
                 a.tolerance.c_str(), a.metric.c_str(), a.statistic.c_str(), unc.c_str());
  }
  return kExitOk;
}

}  // namespace

void add_recommend_command(CLI::App& app, Action& action) {
  const auto [cmd, args] = add_command<RecommendArgs>(app, action, kRecommend, recommend_for);
  cmd->add_option("scene", args->scene, "Scene file (JSON) with the particle")->required();
  add_tolerance(*cmd, args->tolerance);
  cmd->add_option("--study", args->study,
                  "Study folder with guidelines.json (asperity study --out)");
  cmd->add_option("--metric", args->metric,
                  "peak_force, impulse, contact_duration, first_contact_time or "
                  "peak_force+impulse")
      ->check(CLI::IsMember({"peak_force", "impulse", "contact_duration", "first_contact_time",
                             "peak_force+impulse"}))
      ->capture_default_str();
  cmd->add_option("--statistic", args->statistic, "median or p90 over the study's particles")
      ->check(CLI::IsMember({"median", "p90"}))
      ->capture_default_str();
  cmd->add_option("--placement", args->placement,
                  "centroid or lowest (default: the guidelines' first)")
      ->check(CLI::IsMember({"centroid", "lowest"}));
  add_quiet(*cmd, args->quiet, "No summary line on stderr");
}

}  // namespace asperity::app
