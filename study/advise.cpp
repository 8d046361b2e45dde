// `asperity advise`: the advice from a one-particle study at K orientations (study/advise.hpp).
#include "study/advise.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <sstream>

#include "solver/core/error.hpp"
#include "solver/core/quantile.hpp"
#include "solver/io/atomic_file.hpp"
#include "solver/io/json_file.hpp"
#include "study/tables/tables.hpp"

namespace asperity::study {
namespace fs = std::filesystem;
namespace {

using OJson = nlohmann::ordered_json;

// The metrics advise answers (kMetrics' first three; the first contact is 0 by construction
// under the lowest placement the advice study uses).
constexpr const char* kAdviceMetrics[] = {"peak_force", "impulse", "contact_duration"};

std::size_t metric_index(const std::string& metric) {
  for (std::size_t k = 0; k < std::size(kAdviceMetrics); ++k) {
    if (metric == kAdviceMetrics[k]) return k;
  }
  throw InputError("--metric: must be peak_force, impulse or contact_duration (got \"" + metric +
                   "\")");
}

std::string pct(double x) {
  if (!std::isfinite(x)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f %%", 100 * x);
  return buf;
}

std::string candidate_name(const AdviceCandidate& c) {
  std::ostringstream s;
  s << model_name(c.model);
  if (!is_sphere(c.model)) s << " " << c.resolution << " triangles";
  if (c.level > 0) s << ", h = " << c.relative_size << " R at the strike point";
  return s.str();
}

OJson advice_json(const Advice& a) {
  const AdviceCandidate& c = a.pick;
  return {{"metric", a.metric},
          {"tolerance", a.tolerance},
          {"within", a.met},
          {"answer", a.met ? "studied" : "none of the studied"},
          {"model", c.orientations > 0 ? OJson(model_name(c.model)) : OJson()},
          {"resolution", c.orientations > 0 && !is_sphere(c.model) ? OJson(c.resolution) : OJson()},
          {"element_size_rel", c.level > 0 ? OJson(c.relative_size) : OJson()},
          {"error_median", tables::finite_or_null(c.error_median)},
          {"error_worst", tables::finite_or_null(c.error_worst)},
          {"orientations", c.orientations},
          {"reference_uncertainty_median", tables::finite_or_null(a.reference_uncertainty_median)},
          {"reference_uncertainty_worst", tables::finite_or_null(a.reference_uncertainty_worst)},
          {"cpu_seconds_per_impact", tables::finite_or_null(c.cpu)}};
}

std::string advice_text(const Advice& a) {
  const AdviceCandidate& c = a.pick;
  if (c.orientations == 0) return "no candidate was measured";
  std::ostringstream s;
  s << (a.met ? "" : "none of the studied; closest: ") << candidate_name(c) << ": "
    << pct(c.error_median) << " median, " << pct(c.error_worst) << " worst ± "
    << pct(a.reference_uncertainty_worst) << ", " << c.cpu << " s per impact";
  return s.str();
}

}  // namespace

StudyDef write_advice_study(const fs::path& template_file, const AdviseOptions& o,
                            const fs::path& out) {
  io::Json def = io::read_json_file(template_file);
  const std::string name = o.mesh.stem().string();
  def["name"] = "advise-" + name;
  io::Json mesh = io::Json::object();
  mesh["name"] = name;
  mesh["file"] = fs::absolute(o.mesh).string();
  mesh["scale"] = o.scale;
  def["particles"] = io::Json::object();
  def["particles"]["meshes"] = io::Json::array({mesh});
  def["orientations"] = io::Json::object();
  def["orientations"]["random"] = o.orientations;
  fs::create_directories(out);
  const fs::path file = out / "advise_study.json";
  io::write_atomically(file, def.dump(2) + "\n");
  return load_study(file);
}

std::vector<AdviceCandidate> advice_candidates(const tables::StudyCases& s,
                                               const std::string& metric) {
  const std::size_t m = metric_index(metric);
  const StudyDef& def = s.def;
  std::vector<AdviceCandidate> out;
  for (Placement pl : def.placements) {
    for (ModelKind model : def.models) {
      const std::vector<long> resolutions =
          is_sphere(model) ? std::vector<long>{0} : def.resolutions;
      for (long n : resolutions) {
        const int levels = model == ModelKind::fem && def.refinement.applies(n, pl)
                               ? static_cast<int>(def.refinement.sizes.size())
                               : 0;
        for (int level = 0; level <= levels; ++level) {
          std::vector<double> err, cpu;
          for (const ParticleSource& p : def.particles) {
            const tables::CaseData* c = s.find(p.name, model, n, pl, level);
            if (!c) continue;
            const double e = s.err_fem[s.index_of(*c)].metric(m);
            if (!std::isfinite(e)) continue;
            err.push_back(std::abs(e));
            cpu.push_back(c->cpu);
          }
          if (err.empty()) continue;
          out.push_back(
              {.model = model,
               .resolution = n,
               .level = level,
               .relative_size =
                   level > 0 ? def.refinement.sizes[static_cast<std::size_t>(level - 1)] : 0.0,
               .orientations = static_cast<int>(err.size()),
               .error_median = quantile(err, 0.5),
               .error_worst = *std::max_element(err.begin(), err.end()),
               .cpu = quantile(cpu, 0.5)});
        }
      }
    }
  }
  return out;
}

Advice advise(const std::vector<AdviceCandidate>& candidates, const std::string& metric,
              double tolerance, std::pair<double, double> reference_uncertainty) {
  Advice a{.metric = metric,
           .tolerance = tolerance,
           .reference_uncertainty_median = reference_uncertainty.first,
           .reference_uncertainty_worst = reference_uncertainty.second};
  // A candidate counts as measured where every orientation that has a reference measured it.
  int most = 0;
  for (const AdviceCandidate& c : candidates) most = std::max(most, c.orientations);
  const AdviceCandidate* pick = nullptr;
  for (const AdviceCandidate& c : candidates) {
    if (c.orientations == most && c.error_worst <= tolerance && (!pick || c.cpu < pick->cpu))
      pick = &c;
  }
  a.met = pick != nullptr;
  if (!pick) {
    for (const AdviceCandidate& c : candidates) {
      if (c.orientations == most && (!pick || c.error_worst < pick->error_worst)) pick = &c;
    }
  }
  if (pick) a.pick = *pick;
  return a;
}

std::pair<double, double> reference_uncertainty_over(const tables::StudyCases& s,
                                                     const std::string& metric) {
  const std::size_t m = metric_index(metric);
  std::vector<double> u;
  for (const ParticleSource& p : s.def.particles) {
    for (Placement pl : s.def.placements) {
      const tables::StudyCases::Reference* r = s.reference(p.name, pl);
      if (r && std::isfinite(r->uncertainty.metric(m))) u.push_back(r->uncertainty.metric(m));
    }
  }
  if (u.empty()) return {std::nan(""), std::nan("")};
  return {quantile(u, 0.5), *std::max_element(u.begin(), u.end())};
}

OJson write_advice(const tables::StudyCases& s, const AdviseOptions& o, const OJson& run,
                   const fs::path& dir) {
  metric_index(o.metric);
  const auto advise_for = [&](const std::string& metric, double tolerance) {
    return advise(advice_candidates(s, metric), metric, tolerance,
                  reference_uncertainty_over(s, metric));
  };
  const Advice asked = advise_for(o.metric, o.tolerance);
  OJson table = OJson::array();
  std::ostringstream md;
  md << "# Advice for " << o.mesh.filename().string() << "\n\n";
  md << "Within " << pct(o.tolerance) << " on " << o.metric << " at every one of the "
     << asked.pick.orientations << " orientations measured (of " << o.orientations
     << " asked), each against its own reference: **" << advice_text(asked) << "**.\n\n";
  if (run.value("stopped_by_budget", false)) {
    md << "**Stopped by --budget** (" << run.value("budget_minutes", 0.0) << " min) with "
       << run.value("cases_postponed", 0)
       << " cases postponed: this advice rests on the orientations finished. The same command "
          "again goes on where it stopped (finished cases are kept).\n\n";
  }
  md << "Errors are |model − reference| / reference over the orientations (median and worst); "
        "± the reference's uncertainty (worst over the orientations: its Richardson "
        "extrapolation's estimated error); CPU per impact is the median over the orientations "
        "(docs/study.md, \"Advice on a particle\").\n\n";
  md << "| metric | tolerance | answer |\n| --- | ---: | --- |\n";
  for (const char* metric : kAdviceMetrics) {
    for (double tol : tables::kAnswerTolerances) {
      const Advice a = advise_for(metric, tol);
      table.push_back(advice_json(a));
      md << "| " << metric << " | " << pct(tol) << " | " << advice_text(a) << " |\n";
    }
  }
  const OJson j = {{"mesh", fs::absolute(o.mesh).string()},
                   {"advice", advice_json(asked)},
                   {"answers", table},
                   {"run", run}};
  io::write_atomically(dir / "advice.json", j.dump(1) + "\n");
  io::write_atomically(dir / "advice.md", md.str());
  return j;
}

}  // namespace asperity::study
