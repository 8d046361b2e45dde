// candidates.csv: every model and resolution's error against the fem reference over the
// particles, and its median CPU (docs/study.md, "Guidelines").
#include <algorithm>
#include <cmath>

#include "study/curve_measures.hpp"
#include "study/tables/tables.hpp"

namespace asperity::study::tables {

std::vector<CandidateStats> candidate_stats(const StudyCases& s) {
  const StudyDef& def = s.def;
  std::vector<CandidateStats> out;
  if (!s.has_fem_reference()) return out;
  for (Placement pl : def.placements) {
    for (ModelKind m : def.models) {
      const std::vector<long> resolutions =
          m == ModelKind::sphere ? std::vector<long>{0} : def.resolutions;
      for (long n : resolutions) {
        std::vector<double> ep, ei, eb, cpu;
        for (const ParticleSource& p : def.particles) {
          const CaseData* c = s.find(p.name, m, n, pl);
          if (!c) continue;
          const FemErrors& e = s.err_fem[s.index_of(*c)];
          if (!std::isfinite(e.peak) || !std::isfinite(e.impulse)) continue;
          ep.push_back(std::abs(e.peak));
          ei.push_back(std::abs(e.impulse));
          eb.push_back(std::max(ep.back(), ei.back()));
          cpu.push_back(c->cpu);
        }
        if (ep.empty()) continue;
        CandidateStats st{.placement = pl, .model = m, .resolution = n};
        st.particles = static_cast<int>(ep.size());
        st.err["peak_force"] = {quantile(ep, 0.5), quantile(ep, 0.9)};
        st.err["impulse"] = {quantile(ei, 0.5), quantile(ei, 0.9)};
        st.err["peak_force+impulse"] = {quantile(eb, 0.5), quantile(eb, 0.9)};
        st.cpu = quantile(cpu, 0.5);
        out.push_back(std::move(st));
      }
    }
  }
  return out;
}

void write_candidates_table(const std::vector<CandidateStats>& stats,
                            const std::filesystem::path& dir) {
  std::vector<std::vector<OJson>> rows;
  for (const CandidateStats& st : stats) {
    rows.push_back({placement_name(st.placement), model_name(st.model),
                    resolution_or_null(st.model, st.resolution), st.particles,
                    st.err.at("peak_force").first, st.err.at("peak_force").second,
                    st.err.at("impulse").first, st.err.at("impulse").second, st.cpu});
  }
  write_csv(dir / "candidates.csv",
            {"placement", "model", "resolution", "particles", "peak_force_err_median",
             "peak_force_err_p90", "impulse_err_median", "impulse_err_p90", "cpu_seconds_median"},
            rows);
}

}  // namespace asperity::study::tables
