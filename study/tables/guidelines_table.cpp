// guidelines.csv and guidelines.json: the cheapest model and resolution meeting each tolerance
// (docs/study.md, "Guidelines"); `asperity recommend` reads the JSON.
#include <algorithm>
#include <cmath>
#include <iterator>

#include "solver/io/atomic_file.hpp"
#include "study/tables/tables.hpp"

namespace asperity::study::tables {
namespace {

// The range of particle diameters the guidelines were measured on (recommend warns outside):
// the equivalent diameters of the reference meshes, or null when none is known.
OJson particle_diameter_range(const StudyCases& s) {
  const StudyDef& def = s.def;
  const bool has_fem_ref = s.has_fem_reference();
  double d_min = 1e300, d_max = 0;
  for (const ParticleSource& p : def.particles) {
    const CaseData* c = s.find(p.name, has_fem_ref ? ModelKind::fem : def.models.front(),
                               is_sphere(def.models.front()) && !has_fem_ref ? 0 : def.reference,
                               def.placements.front());
    if (c && c->mesh.is_object() && c->mesh.contains("equivalent_radius")) {
      const double d = 2 * c->mesh["equivalent_radius"].get<double>();
      d_min = std::min(d_min, d);
      d_max = std::max(d_max, d);
    }
  }
  return d_max > 0 ? OJson{d_min, d_max} : OJson();
}

}  // namespace

OJson write_guidelines(const StudyCases& s, const std::vector<CandidateStats>& stats,
                       const std::filesystem::path& dir) {
  const StudyDef& def = s.def;
  // For each tolerance, metric and statistic (median, 90th percentile over the particles), the
  // cheapest (median CPU) candidate whose |error| against the fem reference meets it. The fem
  // reference meets every tolerance by definition (error 0).
  const std::vector<double> tolerances = {0.02, 0.05, 0.10};
  std::vector<std::string> metrics(std::begin(kMetrics), std::end(kMetrics));
  metrics.push_back("peak_force+impulse");
  std::vector<std::vector<OJson>> rows;
  OJson guide = OJson::array();
  const int top = static_cast<int>(def.refinement.sizes.size());
  for (Placement pl : def.placements) {
    const auto uncertainty = reference_uncertainty(s, pl);
    for (double tol : tolerances) {
      for (const std::string& metric : metrics) {
        for (int q = 0; q < 2; ++q) {
          auto error = [&](const CandidateStats& c) {
            return q == 0 ? c.err.at(metric).first : c.err.at(metric).second;
          };
          const CandidateStats* best = nullptr;
          for (const CandidateStats& c : stats) {
            if (c.placement == pl && error(c) <= tol && (!best || c.cpu < best->cpu)) best = &c;
          }
          if (!best) continue;
          const double e = error(*best);
          // With the source reference no study case is the one the limit comes from.
          const bool is_ref = def.reference_kind == ReferenceKind::finest &&
                              best->model == ModelKind::fem && best->resolution == def.reference &&
                              best->level == (def.refinement.applies(def.reference, pl) ? top : 0);
          const OJson res = resolution_or_null(best->model, best->resolution);
          const OJson h = best->level > 0 ? OJson(best->relative_size) : OJson();
          const char* statistic = q == 0 ? "median" : "p90";
          // The reference's own uncertainty over the particles (same statistic): a tolerance
          // below it cannot be told apart from the reference's error.
          const auto u = uncertainty.find(metric);
          const double ref_u =
              u == uncertainty.end() ? std::nan("") : (q == 0 ? u->second.first : u->second.second);
          const OJson resolvable = std::isfinite(ref_u) ? OJson(ref_u < tol) : OJson();
          rows.push_back({placement_name(pl), metric, tol, statistic, model_name(best->model), res,
                          h, e, finite_or_null(ref_u), resolvable, best->cpu, is_ref});
          guide.push_back({{"placement", placement_name(pl)},
                           {"metric", metric},
                           {"tolerance", tol},
                           {"statistic", statistic},
                           {"model", model_name(best->model)},
                           {"resolution", res},
                           {"element_size_rel", h},
                           {"error", e},
                           {"reference_uncertainty", finite_or_null(ref_u)},
                           {"resolvable", resolvable},
                           {"cpu_seconds_median", best->cpu},
                           {"is_reference", is_ref}});
        }
      }
    }
  }
  write_csv(
      dir / "guidelines.csv",
      {"placement", "metric", "tolerance", "statistic", "model", "resolution", "element_size_rel",
       "error", "reference_uncertainty", "resolvable", "cpu_seconds_median", "is_reference"},
      rows);
  OJson guidelines = {
      {"study", def.name},
      // The reference the errors are against ("finest" or "source"); model, resolution and size:
      // the study's finest fem, what recommend falls back to when no row meets a tolerance.
      {"reference",
       {{"kind", reference_name(def.reference_kind)},
        {"model", "fem"},
        {"resolution", def.reference},
        {"element_size_rel", top > 0 ? OJson(def.refinement.sizes.back()) : OJson()},
        {"convergence_tolerance", def.refinement.tolerance}}},
      {"speed", def.speed},
      {"particle_diameter_range", particle_diameter_range(s)},
      {"particles", def.particles.size()},
      {"resolutions", def.resolutions},
      {"penalty_alpha", def.penalty_alpha ? OJson(*def.penalty_alpha) : OJson()},
      {"refinement",
       {{"sizes", def.refinement.sizes},
        {"focus_radius", def.refinement.focus_radius},
        {"growth", def.refinement.growth},
        {"max_contact_factor", def.refinement.max_contact_factor}}},
      {"material",
       {{"density", def.material.density},
        {"young", def.material.young},
        {"poisson", def.material.poisson}}},
      {"rows", guide}};
  io::write_atomically(dir / "guidelines.json", guidelines.dump(1) + "\n");
  return guidelines;
}

}  // namespace asperity::study::tables
