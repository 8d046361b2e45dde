// answer.csv and few_hundred.csv: "The answer", what to use for each tolerance, and whether a few
// hundred triangles are enough (docs/study.md, "The answer").
#include <algorithm>
#include <cmath>
#include <iterator>

#include "study/tables/tables.hpp"

namespace asperity::study::tables {
namespace {

double error_of(const CandidateStats& c, const std::string& metric, bool p90) {
  const auto it = c.err.find(metric);
  if (it == c.err.end()) return std::nan("");
  return p90 ? it->second.second : it->second.first;
}

double uncertainty_of(const std::map<std::string, std::pair<double, double>>& u,
                      const std::string& metric, bool p90) {
  const auto it = u.find(metric);
  if (it == u.end()) return std::nan("");
  return p90 ? it->second.second : it->second.first;
}

// The candidate with the smallest error (the cheaper of equal ones), or nullptr.
const CandidateStats* best_of(const std::vector<const CandidateStats*>& cs,
                              const std::string& metric, bool p90) {
  const CandidateStats* best = nullptr;
  for (const CandidateStats* c : cs) {
    const double e = error_of(*c, metric, p90);
    if (!std::isfinite(e)) continue;
    const double b = best ? error_of(*best, metric, p90) : 0;
    if (!best || e < b || (e == b && c->cpu < best->cpu)) best = c;
  }
  return best;
}

std::vector<const CandidateStats*> at_placement(const std::vector<CandidateStats>& stats,
                                                Placement pl) {
  std::vector<const CandidateStats*> out;
  for (const CandidateStats& c : stats) {
    if (c.placement == pl) out.push_back(&c);
  }
  return out;
}

std::vector<OJson> csv_row(const AnswerRow& r) {
  const CandidateStats& c = *r.pick;
  return {placement_name(r.placement),
          r.metric,
          finite_or_null(r.tolerance),
          r.p90 ? "p90" : "median",
          r.met ? "studied" : "none of the studied",
          model_name(c.model),
          resolution_or_null(c.model, c.resolution),
          c.level > 0 ? OJson(c.relative_size) : OJson(),
          finite_or_null(r.error),
          finite_or_null(r.reference_uncertainty),
          finite_or_null(c.cpu)};
}

}  // namespace

std::vector<std::string> answer_metrics(Placement pl) {
  std::vector<std::string> out;
  for (const char* m : kMetrics) {
    if (pl == Placement::lowest && std::string(m) == "first_contact_time") continue;
    out.emplace_back(m);
  }
  out.emplace_back("peak_force+impulse");
  return out;
}

std::vector<AnswerRow> answer_rows(
    const std::vector<CandidateStats>& stats, Placement pl,
    const std::map<std::string, std::pair<double, double>>& uncertainty) {
  const std::vector<const CandidateStats*> cs = at_placement(stats, pl);
  std::vector<AnswerRow> out;
  for (const std::string& metric : answer_metrics(pl)) {
    for (double tol : kAnswerTolerances) {
      for (bool p90 : {false, true}) {
        // The cheapest (median CPU) within the tolerance; else the closest.
        const CandidateStats* pick = nullptr;
        for (const CandidateStats* c : cs) {
          if (error_of(*c, metric, p90) <= tol && (!pick || c->cpu < pick->cpu)) pick = c;
        }
        const bool met = pick != nullptr;
        if (!met) pick = best_of(cs, metric, p90);
        if (!pick) continue;
        out.push_back({.placement = pl,
                       .metric = metric,
                       .tolerance = tol,
                       .p90 = p90,
                       .met = met,
                       .pick = pick,
                       .error = error_of(*pick, metric, p90),
                       .reference_uncertainty = uncertainty_of(uncertainty, metric, p90)});
      }
    }
  }
  return out;
}

std::vector<AnswerRow> few_hundred_rows(
    const std::vector<CandidateStats>& stats, Placement pl,
    const std::map<std::string, std::pair<double, double>>& uncertainty) {
  std::vector<const CandidateStats*> cs;
  for (const CandidateStats* c : at_placement(stats, pl)) {
    if (!is_sphere(c->model) && c->resolution <= kFewHundred) cs.push_back(c);
  }
  std::vector<AnswerRow> out;
  for (const std::string& metric : answer_metrics(pl)) {
    for (bool p90 : {false, true}) {
      const CandidateStats* best = best_of(cs, metric, p90);
      if (!best) continue;
      AnswerRow r{.placement = pl,
                  .metric = metric,
                  .p90 = p90,
                  .pick = best,
                  .error = error_of(*best, metric, p90),
                  .reference_uncertainty = uncertainty_of(uncertainty, metric, p90)};
      for (double tol : kAnswerTolerances) {
        if (r.error <= tol) {
          r.tolerance = tol;
          r.met = true;
          break;
        }
      }
      out.push_back(r);
    }
  }
  return out;
}

void write_answer_tables(const StudyCases& s, const std::vector<CandidateStats>& stats,
                         const std::filesystem::path& dir) {
  std::vector<std::vector<OJson>> answer, few;
  for (Placement pl : s.def.placements) {
    const auto u = reference_uncertainty(s, pl);
    for (const AnswerRow& r : answer_rows(stats, pl, u)) answer.push_back(csv_row(r));
    for (const AnswerRow& r : few_hundred_rows(stats, pl, u)) few.push_back(csv_row(r));
  }
  const std::vector<std::string> header = {"placement",
                                           "metric",
                                           "tolerance",
                                           "statistic",
                                           "answer",
                                           "model",
                                           "resolution",
                                           "element_size_rel",
                                           "error",
                                           "reference_uncertainty",
                                           "cpu_seconds_median"};
  write_csv(dir / "answer.csv", header, answer);
  write_csv(dir / "few_hundred.csv", header, few);
}

}  // namespace asperity::study::tables
