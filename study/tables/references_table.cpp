// references.csv: each particle's reference and the terms of its uncertainty (docs/study.md,
// "The reference" and "The source reference").
#include "study/tables/tables.hpp"

namespace asperity::study::tables {

void write_references_table(const StudyCases& s, const std::filesystem::path& dir) {
  std::vector<std::vector<OJson>> rows;
  for (Placement pl : s.def.placements) {
    for (const ParticleSource& p : s.def.particles) {
      const StudyCases::Reference* r = s.reference(p.name, pl);
      if (!r) continue;
      const bool source = r->kind == ReferenceKind::source;
      std::vector<OJson> row = {
          p.name,
          placement_name(pl),
          source ? OJson() : OJson(r->resolution),
          r->levels,
          finite_or_null(r->values.peak),
          finite_or_null(r->values.impulse),
          finite_or_null(r->values.duration),
          finite_or_null(r->peak.order),
          std::isfinite(r->peak.order) ? OJson(r->peak.observed) : OJson(),
          r->geometry_resolution > 0 ? OJson(r->geometry_resolution) : OJson()};
      // The first-contact time is the free flight's: its terms are not a study finding.
      for (std::size_t k = 0; k + 1 < kMetricCount; ++k) {
        row.push_back(finite_or_null(r->discretization.metric(k)));
        row.push_back(r->geometry_resolution > 0 ? finite_or_null(r->geometry.metric(k)) : OJson());
        row.push_back(finite_or_null(r->uncertainty.metric(k)));
      }
      // The source reference's own columns (empty for "finest"): per metric the extrapolation's
      // order and whether observed, the order of the levels' changes (tables::Extrapolation::
      // changes_order: beside an assumed order, how far from asymptotic the levels are), and the
      // patch check's change (empty where not run).
      row.push_back(reference_name(r->kind));
      for (std::size_t k = 0; k + 1 < kMetricCount; ++k) {
        const Extrapolation& e = r->source_limit[k];
        row.push_back(source ? finite_or_null(e.order) : OJson());
        row.push_back(source && std::isfinite(e.order) ? OJson(e.observed) : OJson());
        row.push_back(source ? finite_or_null(e.changes_order) : OJson());
        row.push_back(source && r->patch_checked ? finite_or_null(r->patch.metric(k)) : OJson());
      }
      // Which levels the source's limit is from ("L1-L3", or "L2-L4" where a fourth ran), the
      // finest one's size over the source's R, and the reference's CPU: every level's, s.
      row.push_back(source ? OJson("L" + std::to_string(r->limit_from) + "-L" +
                                   std::to_string(r->limit_from + 2))
                           : OJson());
      row.push_back(source ? finite_or_null(r->finest_size) : OJson());
      row.push_back(source ? finite_or_null(r->cpu) : OJson());
      rows.push_back(std::move(row));
    }
  }
  std::vector<std::string> header = {
      "particle", "placement",        "resolution",       "levels",         "peak_force",
      "impulse",  "contact_duration", "peak_force_order", "order_observed", "geometry_from"};
  for (std::size_t k = 0; k + 1 < kMetricCount; ++k) {
    for (const char* term : {"_discretization", "_geometry", "_uncertainty"})
      header.push_back(std::string(kMetrics[k]) + term);
  }
  header.push_back("reference");
  for (std::size_t k = 0; k + 1 < kMetricCount; ++k) {
    for (const char* term :
         {"_source_order", "_source_order_observed", "_changes_order", "_patch_change"})
      header.push_back(std::string(kMetrics[k]) + term);
  }
  for (const char* column : {"source_limit_levels", "source_finest_size_rel", "source_cpu_seconds"})
    header.push_back(column);
  write_csv(dir / "references.csv", header, rows);
}

}  // namespace asperity::study::tables
