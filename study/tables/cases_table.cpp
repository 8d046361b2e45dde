// cases.csv: one row per case (docs/study.md, "Tables").
#include "study/tables/tables.hpp"

namespace asperity::study::tables {

void write_cases_table(const StudyCases& s, const std::filesystem::path& dir) {
  const std::vector<std::string> header = {"particle",
                                           "model",
                                           "resolution",
                                           "element_size",
                                           "element_size_rel",
                                           "placement",
                                           "status",
                                           "peak_force",
                                           "impulse",
                                           "contact_duration",
                                           "first_contact_time",
                                           "cpu_seconds",
                                           "steps",
                                           "dt",
                                           "start_gap",
                                           "volume_change_rel",
                                           "centroid_shift_rel",
                                           "max_asperity_rel",
                                           "max_asperity_change_rel",
                                           "peak_force_err",
                                           "impulse_err",
                                           "contact_duration_err",
                                           "first_contact_shift",
                                           "answer",
                                           "converged",
                                           "discretization_error",
                                           "convergence_change",
                                           "extrapolated_peak_force",
                                           "extrapolation_error",
                                           "extrapolation_order",
                                           "order_observed",
                                           "peak_force_err_fem",
                                           "impulse_err_fem",
                                           "contact_duration_err_fem",
                                           "first_contact_shift_fem",
                                           "open_at_end",
                                           "message"};
  std::vector<std::vector<OJson>> rows;
  for (std::size_t i = 0; i < s.cases.size(); ++i) {
    const CaseData& c = s.cases[i];
    const CaseKey& k = c.key;
    // The same model (and element size) at the reference resolution (the sphere has none).
    const CaseData* same = is_sphere(k.model)
                               ? nullptr
                               : s.find(k.particle, k.model, s.def.reference, k.placement, k.level);
    // fem: where this case stands in its refinement sequence (tables/study_cases.hpp).
    // On the answer, the sequence's Richardson limit of the peak force, its estimated error and
    // the order used (observed from three refined levels, or the assumed bracket's middle).
    OJson answer, converged, change, limit, limit_error, order, observed;
    if (k.model == ModelKind::fem) {
      const Sequence* q = s.sequence(k.particle, k.resolution, k.placement);
      answer = q && q->answer == i;
      converged = q && q->answer == i && q->converged;
      if (q && q->answer == i) {
        change = finite_or_null(q->change.peak);
        if (q->extrapolated) {
          limit = finite_or_null(q->limit.peak);
          limit_error = finite_or_null(q->limit_error.peak);
          order = finite_or_null(q->peak.order);
          observed = q->peak.observed;
        }
      }
    }
    const bool ok = StudyCases::usable(&c);
    double pe = std::nan(""), ie = std::nan(""), de = std::nan(""), shift = std::nan("");
    if (ok && StudyCases::usable(same)) {
      pe = rel_err(c.summary["peak_force"], same->summary["peak_force"]);
      ie = rel_err(c.summary["impulse"], same->summary["impulse"]);
      de = rel_err(c.summary["contact_duration"], same->summary["contact_duration"]);
      shift = c.summary["first_contact_time"].get<double>() -
              same->summary["first_contact_time"].get<double>();
    }
    const bool has_mesh = !is_sphere(k.model) && c.mesh.is_object();
    auto mesh_value = [&](const char* key) {
      return has_mesh ? num_or_null(c.mesh, key) : OJson();
    };
    // A contact still open at the end of the window: its duration and impulse are cut short
    // (the "auto" duration should prevent it; a given duration may not).
    OJson open_at_end;
    if (ok) {
      const Curve curve = read_force(c.dir / "force.csv");
      open_at_end = !curve.f.empty() && curve.f.back() > 0;
    }
    rows.push_back({k.particle,
                    model_name(k.model),
                    resolution_or_null(k.model, k.resolution),
                    num_or_null(c.record, "element_size"),
                    k.level > 0 ? OJson(k.relative_size) : OJson(),
                    placement_name(k.placement),
                    c.status,
                    num_or_null(c.summary, "peak_force"),
                    num_or_null(c.summary, "impulse"),
                    num_or_null(c.summary, "contact_duration"),
                    num_or_null(c.summary, "first_contact_time"),
                    num_or_null(c.record, "cpu_seconds"),
                    num_or_null(c.summary, "steps"),
                    num_or_null(c.summary, "dt"),
                    finite_or_null(c.start_gap),
                    mesh_value("volume_change_rel"),
                    mesh_value("centroid_shift_rel"),
                    mesh_value("max_asperity_rel"),
                    mesh_value("max_asperity_change_rel"),
                    finite_or_null(pe),
                    finite_or_null(ie),
                    finite_or_null(de),
                    finite_or_null(shift),
                    answer,
                    converged,
                    finite_or_null(s.discretization_error[i]),
                    change,
                    limit,
                    limit_error,
                    order,
                    observed,
                    finite_or_null(s.err_fem[i].peak),
                    finite_or_null(s.err_fem[i].impulse),
                    finite_or_null(s.err_fem[i].duration),
                    finite_or_null(s.err_fem[i].arrival),
                    open_at_end,
                    c.message.empty() ? OJson() : OJson(c.message)});
  }
  write_csv(dir / "cases.csv", header, rows);
}

}  // namespace asperity::study::tables
