// `asperity recommend`: applies a study's guidelines (guidelines.json) to a new scene: the
// cheapest model and resolution the study found within a tolerance, and whether the scene's
// particle and speed lie inside the range the study measured.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace asperity::study {

struct RecommendOptions {
  double tolerance = 0.05;  // relative, e.g. 0.05 for "5%"
  std::string metric =
      "peak_force+impulse";       // a guidelines metric (kMetrics) or "peak_force+impulse"
  std::string statistic = "p90";  // "median" or "p90" over the study's particles
  std::string placement;          // "" : the guideline file's first
};

// "5%" → 0.05, "0.05" → 0.05; InputError naming `key` otherwise or outside (0, 1).
double parse_tolerance(const std::string& text, const std::string& key);

// The recommendation as JSON (docs/study.md, "recommend"). InputError for a scene without a
// free particle or guidelines without a matching row.
nlohmann::ordered_json recommend(const std::filesystem::path& scene_file,
                                 const std::filesystem::path& guidelines_file,
                                 const RecommendOptions& options);

}  // namespace asperity::study
