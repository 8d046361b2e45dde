// geometry.csv and geometry_answer.csv: the geometry term of a study refining two or more
// resolutions, "is the finest-but-one N enough?" (docs/study.md, "The geometry term").
#include <algorithm>
#include <cmath>
#include <set>

#include "solver/core/quantile.hpp"
#include "study/tables/tables.hpp"

namespace asperity::study::tables {
namespace {

using Answers = std::map<std::pair<std::string, std::string>, std::vector<ConvergedAnswer>>;

double limit_of(const ConvergedAnswer& a, std::size_t m) {
  return m == 0 ? a.limit.peak : m == 1 ? a.limit.impulse : a.limit.duration;
}

// yes: within tol even at the far end of the limit's error; no: beyond it even at the near end,
// or the last change of N alone beyond it (a limit comes only from a monotone sequence, so the
// error is at least that change); else undecided. With no limit (the changes of N not falling),
// the last change of N is the error estimate, as the study's own geometry term takes it: likely
// when within tol (one change, no rate behind it).
std::string verdict(double err, double unc, double last_change, double tol) {
  if (std::isfinite(last_change) && std::abs(last_change) > tol) return "no";
  if (std::isfinite(err)) {
    if (std::abs(err) + unc <= tol) return "yes";
    if (std::abs(err) - unc > tol) return "no";
    return "undecided";
  }
  return std::isfinite(last_change) ? "likely" : "undecided";
}

// At the median, as the guidelines count it (met when half the particles are within): yes when
// half say yes; likely when half say yes or likely; no when more than half say no (fewer than half
// can be within); else undecided.
std::string median_verdict(const std::vector<std::string>& v) {
  const auto n = static_cast<long>(v.size());
  const long half = (n + 1) / 2;
  const auto count = [&](const char* w) { return std::count(v.begin(), v.end(), w); };
  if (count("yes") >= half) return "yes";
  if (count("yes") + count("likely") >= half) return "likely";
  if (count("no") > n - half) return "no";
  return "undecided";
}

double median_of(const std::vector<double>& v) {
  return quantile(v, 0.5);
}

// One particle's sequence in N per metric; the N -> infinity limit and its error per metric.
void sequence_in_n(const std::string& particle, const std::string& placement,
                   const std::vector<ConvergedAnswer>& by_n, GeometryTerm& out,
                   Extrapolation inf[kGeometryMetricCount]) {
  const std::size_t count = by_n.size();
  for (std::size_t m = 0; m < kGeometryMetricCount; ++m) {
    std::vector<double> values, s;
    for (const ConvergedAnswer& a : by_n) {
      values.push_back(limit_of(a, m));
      // The surface edge length over the coarsest N's.
      s.push_back(std::sqrt(static_cast<double>(by_n.front().resolution) /
                            static_cast<double>(a.resolution)));
    }
    inf[m] = {};
    if (count >= 3) {
      const Extrapolation e = richardson(s, values);
      if (e.observed) inf[m] = e;
    }
    for (std::size_t k = 0; k < count; ++k) {
      GeometryRow r{.particle = particle,
                    .placement = placement,
                    .metric = m,
                    .resolution = by_n[k].resolution,
                    .value = values[k],
                    .discretization_error = by_n[k].limit_error.metric(m)};
      if (k > 0) r.change = (values[k] - values[k - 1]) / values[k];
      if (k >= 2) {
        const Extrapolation e =
            richardson({s[k - 2], s[k - 1], s[k]}, {values[k - 2], values[k - 1], values[k]});
        if (e.observed) r.order_observed = e.order;
      }
      if (std::isfinite(inf[m].limit)) r.error_vs_limit = (values[k] - inf[m].limit) / inf[m].limit;
      out.sequence.push_back(r);
    }
    out.sequence.push_back({.particle = particle,
                            .placement = placement,
                            .metric = m,
                            .resolution = 0,
                            .value = inf[m].limit,
                            .limit_error = inf[m].error});
  }
}

}  // namespace

std::map<std::pair<std::string, std::string>, std::vector<ConvergedAnswer>> converged_answers(
    const StudyCases& s) {
  Answers out;
  const int levels = static_cast<int>(s.def.refinement.sizes.size());
  for (const ParticleSource& p : s.def.particles) {
    for (Placement pl : s.def.placements) {
      for (long n : s.def.resolutions) {
        // Every refined level ran (a failed one would make the limit another extrapolation).
        const Sequence* q = s.sequence(p.name, n, pl);
        if (!q || !q->extrapolated || q->refined != levels) continue;
        out[{p.name, placement_name(pl)}].push_back({n, q->limit, q->limit_error});
      }
    }
  }
  for (auto& [key, by_n] : out) {
    std::sort(by_n.begin(), by_n.end(),
              [](const auto& a, const auto& b) { return a.resolution < b.resolution; });
  }
  return out;
}

GeometryTerm geometry_term(const Answers& answers) {
  GeometryTerm out;
  for (const auto& [key, by_n] : answers) {
    if (by_n.size() < 2) continue;
    Extrapolation inf[kGeometryMetricCount];
    const std::size_t first = out.sequence.size();
    sequence_in_n(key.first, key.second, by_n, out, inf);
    // The resolution asked about: the finest but one; the finest's change from it is the last
    // step of N.
    const long asked = by_n[by_n.size() - 2].resolution, finest = by_n.back().resolution;
    for (std::size_t m = 0; m < kGeometryMetricCount; ++m) {
      const GeometryRow *at = nullptr, *last = nullptr;
      for (std::size_t i = first; i < out.sequence.size(); ++i) {
        const GeometryRow& r = out.sequence[i];
        if (r.metric != m) continue;
        if (r.resolution == asked) at = &r;
        if (r.resolution == finest) last = &r;
      }
      GeometryAnswerRow a{.particle = key.first,
                          .placement = key.second,
                          .metric = m,
                          .resolution = asked,
                          .value = at->value,
                          .limit = inf[m].limit,
                          .limit_error = inf[m].error,
                          .error = at->error_vs_limit,
                          .last_change = last->change,
                          .discretization_error = at->discretization_error};
      const bool has_limit = std::isfinite(a.error);
      a.error_estimate = std::abs(has_limit ? a.error : a.last_change);
      a.estimate_from = has_limit ? "limit" : "last change";
      for (std::size_t t = 0; t < std::size(kGeometryTolerances); ++t) {
        a.within[t] = verdict(a.error, std::isfinite(a.limit_error) ? a.limit_error : 0,
                              a.last_change, kGeometryTolerances[t]);
      }
      out.answer.push_back(a);
    }
  }
  // The median over the particles (per placement and metric) of each particle's error estimate
  // (|error| against the limit where there is one, else |last change|) and of the limits' errors.
  std::set<std::string> placements;
  for (const GeometryAnswerRow& r : out.answer) placements.insert(r.placement);
  const std::size_t per_particle = out.answer.size();
  for (const std::string& pl : placements) {
    for (std::size_t m = 0; m < kGeometryMetricCount; ++m) {
      std::vector<const GeometryAnswerRow*> rs;
      for (std::size_t i = 0; i < per_particle; ++i) {
        if (out.answer[i].placement == pl && out.answer[i].metric == m)
          rs.push_back(&out.answer[i]);
      }
      std::vector<double> ests, uncs, changes, disc;
      std::set<std::string> sources;
      for (const GeometryAnswerRow* r : rs) {
        if (std::isfinite(r->error_estimate)) ests.push_back(r->error_estimate);
        if (std::isfinite(r->limit_error)) uncs.push_back(r->limit_error);
        if (std::isfinite(r->last_change)) changes.push_back(std::abs(r->last_change));
        if (std::isfinite(r->discretization_error)) disc.push_back(r->discretization_error);
        sources.insert(r->estimate_from);
      }
      GeometryAnswerRow med{
          .particle = "median",
          .placement = pl,
          .metric = m,
          .resolution = rs.front()->resolution,
          .limit_error = uncs.size() == rs.size() ? median_of(uncs) : std::nan(""),
          .last_change = median_of(changes),
          .error_estimate = median_of(ests),
          .discretization_error = median_of(disc),
          .estimate_from = sources.size() == 1 ? *sources.begin() : "limit or last change"};
      for (std::size_t t = 0; t < std::size(kGeometryTolerances); ++t) {
        std::vector<std::string> v;
        for (const GeometryAnswerRow* r : rs) v.push_back(r->within[t]);
        med.within[t] = median_verdict(v);
      }
      out.answer.push_back(med);
    }
  }
  return out;
}

void write_geometry_tables(const GeometryTerm& g, const std::filesystem::path& dir) {
  if (g.answer.empty()) {
    std::filesystem::remove(dir / "geometry.csv");
    std::filesystem::remove(dir / "geometry_answer.csv");
    return;
  }
  const auto resolution = [](long n) { return n > 0 ? OJson(n) : OJson("inf"); };
  std::vector<std::vector<OJson>> rows;
  for (const GeometryRow& r : g.sequence) {
    rows.push_back({r.particle, r.placement, kMetrics[r.metric], resolution(r.resolution),
                    finite_or_null(r.value), finite_or_null(r.discretization_error),
                    finite_or_null(r.change), finite_or_null(r.order_observed),
                    finite_or_null(r.error_vs_limit), finite_or_null(r.limit_error)});
  }
  write_csv(dir / "geometry.csv",
            {"particle", "placement", "metric", "resolution", "value", "discretization_error",
             "change", "order_observed", "error_vs_limit", "limit_error"},
            rows);
  rows.clear();
  for (const GeometryAnswerRow& r : g.answer) {
    rows.push_back({r.particle, r.placement, kMetrics[r.metric], r.resolution,
                    finite_or_null(r.value), finite_or_null(r.limit), finite_or_null(r.limit_error),
                    finite_or_null(r.error), finite_or_null(r.last_change),
                    finite_or_null(r.error_estimate), r.estimate_from,
                    finite_or_null(r.discretization_error), r.within[0], r.within[1], r.within[2]});
  }
  write_csv(dir / "geometry_answer.csv",
            {"particle", "placement", "metric", "resolution", "value", "limit", "limit_error",
             "error", "last_change", "error_estimate", "estimate_from", "discretization_error",
             "within_1pct", "within_2pct", "within_5pct"},
            rows);
}

}  // namespace asperity::study::tables
