// candidates.csv: every model and resolution's error against the fem reference over the
// particles, and its median CPU (docs/study.md, "Guidelines").
#include <algorithm>
#include <cmath>

#include "solver/core/quantile.hpp"
#include "study/tables/tables.hpp"

namespace asperity::study::tables {

std::vector<CandidateStats> candidate_stats(const StudyCases& s) {
  const StudyDef& def = s.def;
  std::vector<CandidateStats> out;
  if (!s.has_reference()) return out;
  for (Placement pl : def.placements) {
    for (ModelKind m : def.models) {
      const std::vector<long> resolutions = is_sphere(m) ? std::vector<long>{0} : def.resolutions;
      for (long n : resolutions) {
        const int levels = m == ModelKind::fem && def.refinement.applies(n, pl)
                               ? static_cast<int>(def.refinement.sizes.size())
                               : 0;
        for (int level = 0; level <= levels; ++level) {
          std::vector<double> e[kMetricCount], eb, cpu;
          for (const ParticleSource& p : def.particles) {
            const CaseData* c = s.find(p.name, m, n, pl, level);
            if (!c) continue;
            const FemErrors& fe = s.err_fem[s.index_of(*c)];
            bool all = true;
            for (std::size_t k = 0; k < kMetricCount; ++k) all = all && std::isfinite(fe.metric(k));
            if (!all) continue;
            for (std::size_t k = 0; k < kMetricCount; ++k) e[k].push_back(std::abs(fe.metric(k)));
            eb.push_back(std::max(e[0].back(), e[1].back()));
            cpu.push_back(c->cpu);
          }
          if (eb.empty()) continue;
          CandidateStats st{
              .placement = pl,
              .model = m,
              .resolution = n,
              .level = level,
              .relative_size =
                  level > 0 ? def.refinement.sizes[static_cast<std::size_t>(level - 1)] : 0.0};
          st.particles = static_cast<int>(eb.size());
          for (std::size_t k = 0; k < kMetricCount; ++k)
            st.err[kMetrics[k]] = {quantile(e[k], 0.5), quantile(e[k], 0.9)};
          st.err["peak_force+impulse"] = {quantile(eb, 0.5), quantile(eb, 0.9)};
          st.cpu = quantile(cpu, 0.5);
          out.push_back(std::move(st));
        }
      }
    }
  }
  return out;
}

std::map<std::string, std::pair<double, double>> reference_uncertainty(const StudyCases& s,
                                                                       Placement pl) {
  std::vector<double> u[kMetricCount], ub;
  for (const ParticleSource& p : s.def.particles) {
    const StudyCases::Reference* r = s.reference(p.name, pl);
    if (!r) continue;
    for (std::size_t k = 0; k < kMetricCount; ++k) u[k].push_back(r->uncertainty.metric(k));
    ub.push_back(std::max(r->uncertainty.peak, r->uncertainty.impulse));
  }
  std::map<std::string, std::pair<double, double>> out;
  if (ub.empty()) return out;
  for (std::size_t k = 0; k < kMetricCount; ++k)
    out[kMetrics[k]] = {quantile(u[k], 0.5), quantile(u[k], 0.9)};
  out["peak_force+impulse"] = {quantile(ub, 0.5), quantile(ub, 0.9)};
  return out;
}

void write_candidates_table(const std::vector<CandidateStats>& stats,
                            const std::filesystem::path& dir) {
  std::vector<std::vector<OJson>> rows;
  for (const CandidateStats& st : stats) {
    std::vector<OJson> row = {placement_name(st.placement), model_name(st.model),
                              resolution_or_null(st.model, st.resolution),
                              st.level > 0 ? OJson(st.relative_size) : OJson(), st.particles};
    for (const char* m : kMetrics) {
      row.push_back(st.err.at(m).first);
      row.push_back(st.err.at(m).second);
    }
    row.push_back(st.cpu);
    rows.push_back(std::move(row));
  }
  std::vector<std::string> header = {"placement", "model", "resolution", "element_size_rel",
                                     "particles"};
  for (const char* m : kMetrics) {
    header.push_back(std::string(m) + "_err_median");
    header.push_back(std::string(m) + "_err_p90");
  }
  header.push_back("cpu_seconds_median");
  write_csv(dir / "candidates.csv", header, rows);
}

}  // namespace asperity::study::tables
