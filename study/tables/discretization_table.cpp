// discretization.csv: geometry against discretization per placement and resolution, over the
// particles whose fem sequence was refined, and what a converged answer costs (docs/study.md,
// "Geometry and discretization").
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "solver/core/quantile.hpp"
#include "study/tables/tables.hpp"

namespace asperity::study::tables {
namespace {

// Median and 90th percentile of the finite values, null when there are none.
std::pair<OJson, OJson> spread_of(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return {OJson(), OJson()};
  return {finite_or_null(quantile(v, 0.5)), finite_or_null(quantile(v, 0.9))};
}

bool has(const std::vector<std::string>& v, const std::string& x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}

}  // namespace

void write_discretization_table(const StudyCases& s, const std::filesystem::path& dir) {
  std::vector<Placement> placements = s.def.placements;
  std::sort(placements.begin(), placements.end(), [](Placement a, Placement b) {
    return std::string(placement_name(a)) < placement_name(b);
  });
  std::vector<long> resolutions = s.def.resolutions;
  std::sort(resolutions.begin(), resolutions.end());
  std::vector<std::vector<OJson>> rows;
  for (Placement pl : placements) {
    // The finest resolution with a usable fem case, and the limit of its refined answer per
    // particle: the reference the geometry effect compares with.
    long finest = 0;
    for (const CaseData& c : s.cases) {
      if (c.key.model == ModelKind::fem && c.key.placement == pl && StudyCases::usable(&c))
        finest = std::max(finest, c.key.resolution);
    }
    for (long n : resolutions) {
      std::vector<std::size_t> here, answers;  // usable fem cases at (pl, n); refined answers
      std::vector<std::string> refined;        // the particles of `answers`
      for (std::size_t i = 0; i < s.cases.size(); ++i) {
        const CaseData& c = s.cases[i];
        if (c.key.model != ModelKind::fem || c.key.placement != pl || c.key.resolution != n ||
            !StudyCases::usable(&c))
          continue;
        here.push_back(i);
        const Sequence* q = s.sequence(c.key.particle, n, pl);
        if (q && q->answer == i && c.key.level > 0) {
          answers.push_back(i);
          refined.push_back(c.key.particle);
        }
      }
      if (answers.empty()) continue;
      int converged = 0;
      std::vector<double> coarse_err, coarse_cpu, finest_err, limit_err, geometry, change;
      for (std::size_t i : here) {
        const CaseData& c = s.cases[i];
        if (c.key.level == 0 && has(refined, c.key.particle)) {
          coarse_err.push_back(std::abs(s.discretization_error[i]));
          coarse_cpu.push_back(c.cpu);
        }
      }
      for (std::size_t i : answers) {
        const CaseData& c = s.cases[i];
        const Sequence* q = s.sequence(c.key.particle, n, pl);
        converged += q->converged ? 1 : 0;
        finest_err.push_back(std::abs(s.discretization_error[i]));
        change.push_back(q->change.peak);
        if (!q->extrapolated) continue;
        limit_err.push_back(q->limit_error.peak);
        const Sequence* ref = s.sequence(c.key.particle, finest, pl);
        if (n != finest && ref && ref->extrapolated)
          geometry.push_back(std::abs(q->limit.peak / ref->limit.peak - 1));
      }
      // What a converged answer costs: the CPU of the whole sequence (every level) per particle,
      // in the cases' order; the worst is the first of the largest.
      std::vector<std::pair<std::string, double>> per_particle;
      for (std::size_t i : here) {
        const CaseData& c = s.cases[i];
        if (!has(refined, c.key.particle)) continue;
        auto it = std::find_if(per_particle.begin(), per_particle.end(),
                               [&](const auto& p) { return p.first == c.key.particle; });
        if (it == per_particle.end()) {
          per_particle.emplace_back(c.key.particle, 0.0);
          it = per_particle.end() - 1;
        }
        it->second += c.cpu;
      }
      std::vector<double> sequence_cpu;
      for (const auto& p : per_particle) sequence_cpu.push_back(p.second);
      const auto worst =
          std::max_element(per_particle.begin(), per_particle.end(),
                           [](const auto& a, const auto& b) { return a.second < b.second; });
      const auto [coarse_med, coarse_p90] = spread_of(coarse_err);
      const auto [limit_med, limit_p90] = spread_of(limit_err);
      const auto [geo_med, geo_p90] = spread_of(geometry);
      const auto [cpu_med, cpu_p90] = spread_of(sequence_cpu);
      rows.push_back({placement_name(pl), n, answers.size(), converged, coarse_med, coarse_p90,
                      spread_of(finest_err).first, limit_med, limit_p90, geo_med, geo_p90,
                      spread_of(change).first, per_particle.size(), cpu_med, cpu_p90, worst->second,
                      worst->first, spread_of(coarse_cpu).first});
    }
  }
  write_csv(
      dir / "discretization.csv",
      {"placement", "resolution", "sequences", "converged", "coarse_error_median",
       "coarse_error_p90", "finest_level_error_median", "limit_error_median", "limit_error_p90",
       "geometry_median", "geometry_p90", "last_change_median", "particles", "sequence_cpu_median",
       "sequence_cpu_p90", "sequence_cpu_worst", "worst_particle", "coarse_cpu_median"},
      rows);
}

}  // namespace asperity::study::tables
