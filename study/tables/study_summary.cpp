// study_summary.json: counts, cost and cost growth beside the published study's
// (docs/study.md, "Tables").
#include <cmath>
#include <exception>

#include "solver/core/error.hpp"
#include "solver/core/quantile.hpp"
#include "solver/io/atomic_file.hpp"
#include "solver/io/json_file.hpp"
#include "study/tables/tables.hpp"

namespace asperity::study::tables {
namespace fs = std::filesystem;
namespace {

// Total CPU of every done case (whenever it ran) and by model, with the meshing once per mesh.
std::pair<double, std::map<std::string, double>> cpu_totals(const StudyCases& s) {
  const StudyDef& def = s.def;
  double total = 0;
  std::map<std::string, double> by_model;
  for (const CaseData& c : s.cases) {
    if (std::isfinite(c.cpu)) {
      total += c.cpu;
      by_model[model_name(c.key.model)] += c.cpu;
    }
    // One case per mesh: the first placement's coarse case of the first model (a refined fem
    // case reads the same mesh.json).
    if (c.mesh.is_object() && !is_sphere(c.key.model) && c.key.level == 0 &&
        c.key.placement == def.placements.front() && c.key.model == def.models.front()) {
      total += c.mesh.value("mesh_cpu_seconds", 0.0);
      by_model["meshing"] += c.mesh.value("mesh_cpu_seconds", 0.0);
    }
  }
  // The source reference's levels (and their contact-local surfaces) as a model of their own.
  for (const CaseData& c : s.source_cases) {
    if (std::isfinite(c.cpu)) {
      total += c.cpu;
      by_model["source-reference"] += c.cpu;
    }
  }
  return {total, by_model};
}

// Median CPU of a model at one resolution over the particles and placements.
double median_cpu(const StudyCases& s, ModelKind m, long n) {
  std::vector<double> v;
  for (Placement pl : s.def.placements) {
    for (const ParticleSource& p : s.def.particles) {
      const CaseData* c = s.find(p.name, m, n, pl);
      if (StudyCases::usable(c)) v.push_back(c->cpu);
    }
  }
  return quantile(v, 0.5);
}

// Wall time of every run that computed cases in this folder (a resumed study adds up; a rerun
// that only kept cases adds nothing), so the report states what the cases took, not the last,
// possibly empty, rerun. Returns (seconds, runs).
std::pair<double, int> wall_computing(const StudyOutcome& run, const fs::path& dir) {
  double wall = run.ran > 0 ? run.wall_seconds : 0.0;
  int runs = run.ran > 0 ? 1 : 0;
  if (const fs::path prev = dir / "study_summary.json"; fs::exists(prev)) {
    try {
      const io::Json j = io::read_json_file(prev);
      wall += j.value("wall_seconds_computing", 0.0);
      runs += j.value("runs_computing", 0);
    } catch (const std::exception&) {
      // an unreadable earlier summary only loses the earlier runs' wall time
    }
  }
  return {wall, runs};
}

}  // namespace

OJson read_published_study(const fs::path& file) {
  const OJson j = OJson::parse(io::read_json_file(file).dump());
  auto need = [&](const char* key, bool number) -> const OJson& {
    if (!j.contains(key) || (number ? !j[key].is_number() : !j[key].is_string())) {
      throw InputError(file.string() + ": key \"" + key + "\": missing or not a " +
                       (number ? "number" : "string"));
    }
    return j[key];
  };
  const OJson& cpu_100 = need("cpu_seconds_100", true);
  const OJson& cpu_1000 = need("cpu_seconds_1000", true);
  return {{"source", need("source", false)},
          {"simulations", need("simulations", true)},
          {"cpu_seconds_100", cpu_100},
          {"cpu_seconds_1000", cpu_1000},
          {"cpu_growth_100_1000", cpu_1000.get<double>() / cpu_100.get<double>()},
          {"peak_force_variation_max", need("peak_force_variation_max", true)},
          {"impulse_variation_max", need("impulse_variation_max", true)}};
}

OJson write_study_summary(const StudyCases& s, const std::vector<CpuFit>& fits,
                          const OJson& published, const StudyOutcome& run, const fs::path& dir) {
  const StudyDef& def = s.def;
  const auto [cpu_total, cpu_by_model] = cpu_totals(s);
  const auto [wall, runs] = wall_computing(run, dir);
  const bool has_fem_ref = s.has_fem_reference();
  const bool has_100_1000 = has_fem_ref &&
                            std::count(def.resolutions.begin(), def.resolutions.end(), 100) &&
                            std::count(def.resolutions.begin(), def.resolutions.end(), 1000);
  const long lo = def.resolutions.front(), hi = def.resolutions.back();
  OJson fit_json = OJson::array();
  for (const CpuFit& f : fits) {
    fit_json.push_back({{"model", model_name(f.model)},
                        {"placement", placement_name(f.placement)},
                        {"exponent", f.exponent},
                        {"coefficient", f.coefficient}});
  }
  OJson summary = {
      {"study", def.name},
      {"particles", def.particles.size()},
      {"resolutions", def.resolutions},
      {"models", OJson::array()},
      {"placements", OJson::array()},
      {"cases", static_cast<int>(s.cases.size() + s.source_cases.size())},
      {"done", s.done},
      {"failed", s.failed},
      {"cpu_seconds_total", cpu_total},
      {"cpu_seconds_by_model", cpu_by_model},
      {"wall_seconds_computing", wall},
      {"runs_computing", runs},
      {"last_run",
       {{"wall_seconds", run.wall_seconds},
        {"cpu_seconds", run.cpu_seconds},
        {"ran", run.ran},
        {"kept", run.skipped},
        {"failed", run.failed}}},
      {"fem_cpu_growth", has_fem_ref ? OJson{{"from", lo},
                                             {"to", hi},
                                             {"ratio", median_cpu(s, ModelKind::fem, hi) /
                                                           median_cpu(s, ModelKind::fem, lo)}}
                                     : OJson()},
      {"fem_cpu_growth_100_1000", has_100_1000 ? OJson(median_cpu(s, ModelKind::fem, 1000) /
                                                       median_cpu(s, ModelKind::fem, 100))
                                               : OJson()},
      {"cpu_fit", fit_json},
      {"published", published}};
  for (ModelKind m : def.models) summary["models"].push_back(model_name(m));
  for (Placement p : def.placements) summary["placements"].push_back(placement_name(p));
  io::write_atomically(dir / "study_summary.json", summary.dump(1) + "\n");
  return summary;
}

}  // namespace asperity::study::tables
