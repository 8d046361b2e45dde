// classification.csv: each model and resolution's force curve against the converged fem
// reference curve (docs/study.md, "Classification").
#include <algorithm>
#include <cmath>

#include "study/curve_measures.hpp"
#include "study/tables/tables.hpp"

namespace asperity::study::tables {

std::vector<Classification> classify_resolutions(const StudyCases& s) {
  const StudyDef& def = s.def;
  const ClassifyCriteria criteria;
  std::vector<Classification> out;
  for (const ParticleSource& p : def.particles) {
    for (ModelKind m : def.models) {
      if (is_sphere(m)) continue;
      for (Placement pl : def.placements) {
        // Against the converged fem reference (issue 12): the reference answer at the finest
        // resolution, whatever the model; each model's coarse case at every resolution.
        const StudyCases::Reference* r = s.reference(p.name, pl);
        if (!r) continue;
        const CaseData* ref = &s.reference_case(*r);
        const Curve rc = read_force(ref->dir / "force.csv");
        const double d_ref = ref->summary["contact_duration"].get<double>();
        const CurveShape rs = curve_shape(rc.t, rc.f);
        for (long n : def.resolutions) {
          const CaseData* c = s.find(p.name, m, n, pl);
          if (!StudyCases::usable(c) || c == ref) continue;
          const Curve cc = read_force(c->dir / "force.csv");
          const double t_end =
              std::max(rc.t.empty() ? 0.0 : rc.t.back(), cc.t.empty() ? 0.0 : cc.t.back());
          const double lag = cross_correlation_lag(rc.t, rc.f, cc.t, cc.f, t_end);
          const double ratio =
              d_ref > 0 ? c->summary["contact_duration"].get<double>() / d_ref : std::nan("");
          const CurveShape cs = curve_shape(cc.t, cc.f);
          const double onset = s.err_fem[s.index_of(*c)].arrival;
          out.push_back({.particle = p.name,
                         .model = m,
                         .placement = pl,
                         .resolution = n,
                         .lag = lag,
                         .lag_rel = d_ref > 0 ? lag / d_ref : std::nan(""),
                         .duration_ratio = ratio,
                         .onset_shift_rel = onset,
                         .skewness = cs.skewness,
                         .skewness_reference = rs.skewness,
                         .cls = classify(std::isfinite(onset) ? onset : 0, ratio,
                                         cs.skewness - rs.skewness, criteria)});
        }
      }
    }
  }
  return out;
}

void write_classification_table(const std::vector<Classification>& rows,
                                const std::filesystem::path& dir) {
  std::vector<std::vector<OJson>> table;
  for (const Classification& r : rows) {
    table.push_back({r.particle, model_name(r.model), placement_name(r.placement), r.resolution,
                     r.lag, finite_or_null(r.lag_rel), finite_or_null(r.onset_shift_rel),
                     finite_or_null(r.duration_ratio), r.skewness, r.skewness_reference,
                     r.skewness - r.skewness_reference, r.cls});
  }
  write_csv(
      dir / "classification.csv",
      {"particle", "model", "placement", "resolution", "lag", "lag_rel", "first_contact_shift_rel",
       "duration_ratio", "skewness", "skewness_reference", "skewness_diff", "class"},
      table);
}

}  // namespace asperity::study::tables
