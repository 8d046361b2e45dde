// unreferenced.csv: the particles (and orientations) with no reference, and why (docs/study.md,
// "Tables"). A reference needs every level of its sequence usable; a level that ended unstable
// (an inverted element, energy growth: the run's own checks) takes its particle out of every error
// of the study. Without this table that particle would only be missing from references.csv,
// and a median "over the particles" would silently be over fewer of them.
#include "study/tables/tables.hpp"

namespace asperity::study::tables {

namespace {

// The cases a particle's reference is made of: the source reference's levels on the patch, or the
// fem sequence (the coarse case and every refined level) at the finest resolution.
bool makes_reference(const StudyDef& def, const CaseKey& k) {
  if (def.reference_kind == ReferenceKind::source) return k.source_patch == 1;
  return k.source_patch == 0 && k.model == ModelKind::fem && k.resolution == def.reference;
}

}  // namespace

void write_unreferenced_table(const StudyCases& s, const std::filesystem::path& dir) {
  std::vector<std::vector<OJson>> rows;
  const std::vector<CaseData>& pool =
      s.def.reference_kind == ReferenceKind::source ? s.source_cases : s.cases;
  for (Placement pl : s.def.placements) {
    for (const ParticleSource& p : s.def.particles) {
      if (s.reference(p.name, pl)) continue;
      std::string why;
      for (const CaseData& c : pool) {
        if (c.key.particle != p.name || c.key.placement != pl || !makes_reference(s.def, c.key) ||
            StudyCases::usable(&c))
          continue;
        // A failed case's message is its failed.json's; an unstable run's, its summary.json's.
        std::string message = c.message;
        if (message.empty() && c.summary.is_object()) message = c.summary.value("message", "");
        why += (why.empty() ? "" : "; ") + c.key.dir_name() + " " + c.status +
               (message.empty() ? "" : ": " + message);
      }
      if (why.empty()) why = "no usable sequence";
      rows.push_back({p.name, placement_name(pl), why});
    }
  }
  write_csv(dir / "unreferenced.csv", {"particle", "placement", "why"}, rows);
}

}  // namespace asperity::study::tables
