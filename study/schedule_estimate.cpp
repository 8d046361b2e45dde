// A study's schedule on paper (schedule_estimate.hpp).
#include "study/schedule_estimate.hpp"

#include <algorithm>
#include <charconv>
#include <map>
#include <optional>
#include <tuple>

#include "cluster/pool_replay.hpp"
#include "solver/core/error.hpp"
#include "solver/core/quantile.hpp"
#include "study/case_weight.hpp"

namespace asperity::study {
namespace {

// A case as the table spells it: model, resolution, element_size_rel (the refined level's h over
// R, empty for a coarse case), exactly as written, so that equal cells are the same kind.
using Kind = std::tuple<std::string, std::string, std::string>;

// The columns the replay reads.
struct Columns {
  std::size_t particle, model, resolution, size, cpu;
  explicit Columns(const io::CsvTable& t)
      : particle(t.required("particle")),
        model(t.required("model")),
        resolution(t.required("resolution")),
        size(t.required("element_size_rel")),
        cpu(t.required("cpu_seconds")) {}
};

const std::string& cell(const io::CsvTable& t, std::size_t k, std::size_t i) {
  if (i >= t.rows[k].size())
    throw InputError("line " + std::to_string(k + 2) + ": fewer fields than the header");
  return t.rows[k][i];
}

double number_of(const std::string& text, const std::string& what) {
  double x = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), x);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size())
    throw InputError(what + " \"" + text + "\" is not a number");
  return x;
}

// The key case_weight reads: the model, the triangle count (0 for a sphere), and the refined
// level (any level ≥ 1 weighs alike: only its h counts).
CostedCase costed(const Kind& kind, double cpu_seconds) {
  const auto& [model, resolution, size] = kind;
  const std::optional<ModelKind> m = model_of(model);
  if (!m) throw InputError("unknown model \"" + model + "\"");
  CaseKey key{.model = *m};
  if (!resolution.empty()) key.resolution = static_cast<long>(number_of(resolution, "resolution"));
  if (!size.empty()) {
    key.level = 1;
    key.relative_size = number_of(size, "element_size_rel");
  }
  return {.key = key, .cpu_seconds = cpu_seconds};
}

}  // namespace

std::vector<CostedCase> measured_cases(const io::CsvTable& t) {
  const Columns c(t);
  std::vector<CostedCase> out;
  for (std::size_t k = 0; k < t.rows.size(); ++k) {
    if (cell(t, k, c.cpu).empty()) continue;
    out.push_back(costed({cell(t, k, c.model), cell(t, k, c.resolution), cell(t, k, c.size)},
                         t.number(k, c.cpu)));
  }
  return out;
}

std::vector<CostedCase> cluster_study_cases(const io::CsvTable& t) {
  const Columns c(t);
  std::map<std::pair<std::string, Kind>, double> cost;  // by particle and kind; the last row wins
  std::map<Kind, std::vector<double>> by_kind;
  std::vector<std::string> particles;  // in the order they first show
  for (std::size_t k = 0; k < t.rows.size(); ++k) {
    const std::string& p = cell(t, k, c.particle);
    if (std::find(particles.begin(), particles.end(), p) == particles.end()) particles.push_back(p);
    if (cell(t, k, c.cpu).empty()) continue;
    const Kind kind{cell(t, k, c.model), cell(t, k, c.resolution), cell(t, k, c.size)};
    const double cpu = t.number(k, c.cpu);
    cost[{p, kind}] = cpu;
    by_kind[kind].push_back(cpu);
  }
  const auto measured = [&](const std::string& p, const Kind& kind) {
    if (const auto it = cost.find({p, kind}); it != cost.end()) return it->second;
    const auto others = by_kind.find(kind);
    if (others == by_kind.end()) {
      throw InputError("no measured case of model \"" + std::get<0>(kind) + "\", resolution \"" +
                       std::get<1>(kind) + "\", element_size_rel \"" + std::get<2>(kind) +
                       "\" to cost " + p + "'s by");
    }
    return spread(others->second).median;
  };
  const std::vector<std::string> resolutions = {"100", "250", "500", "1000", "2000"};
  std::vector<CostedCase> out;
  for (const std::string& p : particles) {
    std::vector<CostedCase> placement;
    for (const char* model : {"fem", "rigid", "rigid-penalty"}) {
      for (const std::string& n : resolutions) {
        const Kind kind{model, n, ""};
        placement.push_back(costed(kind, measured(p, kind)));
      }
    }
    for (const char* model : {"sphere", "sphere-local"}) {
      const Kind kind{model, "", ""};
      placement.push_back(costed(kind, measured(p, kind)));
    }
    for (const std::string& n : resolutions) {
      const std::string at = n == "100" || n == "250" ? "500" : n;
      const double c08 = measured(p, {"fem", at, "0.08"}), c04 = measured(p, {"fem", at, "0.04"});
      const double c02 = c04 * std::max(2.0, c04 / c08);
      placement.push_back(costed({"fem", n, "0.08"}, c08));
      placement.push_back(costed({"fem", n, "0.04"}, c04));
      placement.push_back(costed({"fem", n, "0.02"}, c02));
    }
    // The centroid and lowest placements.
    out.insert(out.end(), placement.begin(), placement.end());
    out.insert(out.end(), placement.begin(), placement.end());
  }
  return out;
}

ScheduleReplay replay_schedule(const std::vector<CostedCase>& cases, int workers) {
  std::vector<double> plan;
  for (const CostedCase& c : cases) plan.push_back(c.cpu_seconds);
  // The study's own order (study_run.cpp, run_cases): a stable sort by falling weight.
  std::vector<std::size_t> order(cases.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return case_weight(cases[a].key) > case_weight(cases[b].key);
  });
  std::vector<double> expensive_first;
  for (std::size_t k : order) expensive_first.push_back(cases[k].cpu_seconds);
  return {.expensive_first = cluster::replay_pool(expensive_first, workers),
          .plan_order = cluster::replay_pool(plan, workers)};
}

}  // namespace asperity::study
