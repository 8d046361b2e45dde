// `asperity recommend SCENE --tolerance 5%`: the cheapest model and resolution a study's
// guidelines give for the scene's particle (study/recommend.hpp). JSON on stdout, a line on stderr.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/commands.hpp"
#include "solver/core/error.hpp"
#include "study/recommend.hpp"

namespace asperity::app {

void add_recommend_command(CLI::App& app, Action& action) {
  struct Args {
    std::filesystem::path scene, study;
    std::string tolerance = "5%", metric = "peak_force+impulse", statistic = "p90", placement;
    bool quiet = false;
  };
  auto args = std::make_shared<Args>();
  auto* cmd = app.add_subcommand(
      "recommend",
      "Cheapest particle model and resolution within a tolerance on peak force / impulse, from a "
      "study's "
      "guidelines (--study DIR, default data/study/guidelines.json); JSON on stdout");
  cmd->add_option("scene", args->scene, "Scene file (JSON) with the particle")->required();
  cmd->add_option("--tolerance", args->tolerance, "Relative tolerance, e.g. 5% or 0.05")
      ->capture_default_str();
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
  cmd->add_flag("-q,--quiet", args->quiet, "No summary line on stderr");
  cmd->callback([args, &action] {
    action = [args] {
      const study::RecommendOptions o{
          .tolerance = study::parse_tolerance(args->tolerance, "--tolerance"),
          .metric = args->metric,
          .statistic = args->statistic,
          .placement = args->placement};
      const std::filesystem::path g = args->study.empty()
                                          ? std::filesystem::path(ASPERITY_DEFAULT_GUIDELINES)
                                          : args->study / "guidelines.json";
      if (!std::filesystem::exists(g))
        throw InputError(g.string() + ": no guidelines (run asperity study first)");
      const nlohmann::ordered_json r = study::recommend(args->scene, g, o);
      std::cout << r.dump(1) << "\n";
      if (!args->quiet) {
        const auto& rec = r["recommendation"];
        // The reference's uncertainty beside the answer: the error is known no better.
        const auto& u = rec["reference_uncertainty"];
        const std::string unc = u.is_number()
                                    ? ", reference uncertain by " +
                                          std::to_string(u.get<double>() * 100).substr(0, 4) + "%"
                                    : "";
        std::fprintf(stderr, "%s: %s%s within %s on %s (%s over the study's particles%s)\n",
                     args->scene.string().c_str(), rec["model"].get<std::string>().c_str(),
                     rec["resolution"].is_null()
                         ? ""
                         : (" at " + rec["resolution"].dump() + " triangles").c_str(),
                     args->tolerance.c_str(), args->metric.c_str(), args->statistic.c_str(),
                     unc.c_str());
      }
      return kExitOk;
    };
  });
}

}  // namespace asperity::app
