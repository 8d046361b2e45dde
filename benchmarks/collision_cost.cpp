// collision_cost RUNS.csv OUT_DIR: the statistics of bench_fem's collisions over the particle set
// (issue 11, item 6; reports/fem/collision_cost.md), computed here, by the C++ that owns the
// median and the least-squares line (solver/core/quantile.hpp, least_squares.hpp), for
// tools/report/collision_cost_table.py, which parses bench_fem's console output into RUNS.csv
// and only formats what this writes.
//
// RUNS.csv: one row per collision, in the order bench_fem ran them (particle, faces, cpu_s,
// steps, dt, dt_element, tets; penalty_scale_min where the run gave it). Writes into OUT_DIR:
// - by_faces.csv: per resolution N, the particles run, the median and worst CPU seconds (the worst
//   particle: the first of the largest, in run order), the medians of steps, dt and tetrahedra;
// - by_particle.csv: per particle that ran 100 and 1000 faces or three resolutions, in run
//   order, the exponent log(cpu_1000 / cpu_100) / log 10, split into the steps' and the work per
//   step's (the cost is steps × work per step), with the tetrahedra, dt/dt_element and least
//   penalty factor at 100 and 1000 (NaN without both), and the least-squares slope of log cpu on
//   log N over every N it ran (NaN under three);
// - summary.csv: one row: the particles, the exponent's and the slope's median, least and largest
//   (with its particle) over by_particle.csv, how many lie above kHighExponent, and how many
//   collisions at 1000 faces take more than kBudgetSeconds (those particles, ';'-joined);
// - exponent_bins.csv: how many exponents lie in each tenth [b/10, (b + 1)/10).
// Numbers to the last bit (17 digits), so the table formats exactly these doubles. Bad input: one
// line naming the file and the problem, exit 2.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "solver/core/least_squares.hpp"
#include "solver/core/quantile.hpp"
#include "solver/io/atomic_file.hpp"
#include "solver/io/csv.hpp"

namespace {

// The item's bounds (issue 11, item 6): a collision at 1000 faces within 2 s of CPU, and the
// exponent of the cost over N at most 1.4 (the steps' 0.5 for dt ∝ h ∝ N^-1/2 plus the work per
// step's 1 for tetrahedra ∝ N, with a little room for the contact).
constexpr double kBudgetSeconds = 2.0, kHighExponent = 1.4;
// The resolutions the exponent spans.
constexpr long kCoarse = 100, kFine = 1000;

struct Run {
  double cpu = 0, steps = 0, dt = 0, dt_element = 0, tets = 0, penalty_scale_min = 1;
};

// The particles in the order they first ran, each with its runs by N.
struct Runs {
  std::vector<std::string> order;
  std::map<std::string, std::map<long, Run>> by_particle;
};

Runs read_runs(const std::string& file) {
  const asperity::io::CsvTable t = asperity::io::read_csv_table(file);
  const std::size_t particle = t.required("particle"), faces = t.required("faces"),
                    cpu = t.required("cpu_s"), steps = t.required("steps"), dt = t.required("dt"),
                    dt_element = t.required("dt_element"), tets = t.required("tets");
  const std::optional<std::size_t> penalty = t.column("penalty_scale_min");
  Runs runs;
  for (std::size_t k = 0; k < t.rows.size(); ++k) {
    const std::string name = particle < t.rows[k].size() ? t.rows[k][particle] : "";
    if (!runs.by_particle.contains(name)) runs.order.push_back(name);
    Run r{.cpu = t.number(k, cpu),
          .steps = t.number(k, steps),
          .dt = t.number(k, dt),
          .dt_element = t.number(k, dt_element),
          .tets = t.number(k, tets)};
    // A run that did not report it (an older bench_fem) had no lowered penalty: factor 1.
    if (penalty && !std::isnan(t.number(k, *penalty))) r.penalty_scale_min = t.number(k, *penalty);
    runs.by_particle[name][std::lround(t.number(k, faces))] = r;
  }
  if (runs.order.empty()) throw asperity::InputError("has no runs");
  return runs;
}

// The median of one field over some runs.
template <class Field>
double median(const std::vector<const Run*>& runs, Field field) {
  std::vector<double> v;
  for (const Run* r : runs) v.push_back(field(*r));
  return asperity::quantile(v, 0.5);
}

std::string by_faces(const Runs& runs) {
  std::vector<long> faces;
  for (const auto& [name, levels] : runs.by_particle)
    for (const auto& [n, run] : levels) faces.push_back(n);
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  asperity::io::CsvWriter csv({"faces", "particles", "cpu_median", "cpu_worst", "worst_particle",
                               "steps_median", "dt_median", "tets_median"},
                              17);
  for (const long n : faces) {
    std::vector<const Run*> at;
    const Run* worst = nullptr;
    std::string worst_name;
    for (const std::string& p : runs.order) {
      const auto& levels = runs.by_particle.at(p);
      const auto it = levels.find(n);
      if (it == levels.end()) continue;
      at.push_back(&it->second);
      if (!worst || it->second.cpu > worst->cpu) worst = &it->second, worst_name = p;
    }
    csv.number(static_cast<double>(n))
        .number(static_cast<double>(at.size()))
        .number(median(at, [](const Run& r) { return r.cpu; }))
        .number(worst->cpu)
        .field(worst_name)
        .number(median(at, [](const Run& r) { return r.steps; }))
        .number(median(at, [](const Run& r) { return r.dt; }))
        .number(median(at, [](const Run& r) { return r.tets; }))
        .end_row();
  }
  return csv.str();
}

// One particle's exponents over N.
struct Exponents {
  std::string particle;
  double exponent = std::nan(""), steps_exponent = std::nan("");
  double least_squares = std::nan("");  // NaN: fewer than three resolutions
  long levels = 0;
  const Run *coarse = nullptr, *fine = nullptr;
};

std::vector<Exponents> exponents(const Runs& runs) {
  std::vector<Exponents> out;
  for (const std::string& p : runs.order) {
    const auto& levels = runs.by_particle.at(p);
    const bool ends = levels.contains(kCoarse) && levels.contains(kFine);
    if (!ends && levels.size() < 3) continue;
    Exponents e{.particle = p, .levels = static_cast<long>(levels.size())};
    if (ends) {
      e.coarse = &levels.at(kCoarse), e.fine = &levels.at(kFine);
      e.exponent = std::log(e.fine->cpu / e.coarse->cpu) / std::log(10.0);
      e.steps_exponent = std::log(e.fine->steps / e.coarse->steps) / std::log(10.0);
    }
    if (levels.size() >= 3) {
      std::vector<double> x, y;
      for (const auto& [n, run] : levels) {
        x.push_back(std::log(static_cast<double>(n)));
        y.push_back(std::log(run.cpu));
      }
      e.least_squares = asperity::fit_line(x, y).slope;
    }
    out.push_back(e);
  }
  return out;
}

std::string by_particle(const std::vector<Exponents>& es) {
  asperity::io::CsvWriter csv(
      {"particle", "exponent", "steps_exponent", "work_per_step_exponent", "least_squares_exponent",
       "levels", "tets_100", "tets_1000", "dt_over_element_100", "dt_over_element_1000",
       "penalty_scale_min_1000", "cpu_1000"},
      17);
  const double none = std::nan("");
  for (const Exponents& e : es) {
    const Run *a = e.coarse, *b = e.fine;
    csv.field(e.particle)
        .number(e.exponent)
        .number(e.steps_exponent)
        .number(e.exponent - e.steps_exponent)
        .number(e.least_squares)
        .number(static_cast<double>(e.levels))
        .number(a ? a->tets : none)
        .number(b ? b->tets : none)
        .number(a ? a->dt / a->dt_element : none)
        .number(b ? b->dt / b->dt_element : none)
        .number(b ? b->penalty_scale_min : none)
        .number(b ? b->cpu : none)
        .end_row();
  }
  return csv.str();
}

// Median, least, largest and the largest's particle (the first, in run order) of one exponent
// over the particles that have it.
struct Spread {
  long particles = 0;
  double median = std::nan(""), least = std::nan(""), largest = std::nan("");
  std::string largest_particle;
  long above_high = 0;
};

template <class Field>
Spread spread(const std::vector<Exponents>& es, Field field) {
  Spread s;
  std::vector<double> v;
  for (const Exponents& e : es) {
    const double x = field(e);
    if (std::isnan(x)) continue;
    v.push_back(x);
    if (s.particles++ == 0 || x > s.largest) s.largest = x, s.largest_particle = e.particle;
    if (s.particles == 1 || x < s.least) s.least = x;
    s.above_high += x > kHighExponent;
  }
  s.median = asperity::quantile(v, 0.5);
  return s;
}

std::string summary(const Runs& runs, const std::vector<Exponents>& es) {
  const Spread e = spread(es, [](const Exponents& x) { return x.exponent; });
  const Spread f = spread(es, [](const Exponents& x) { return x.least_squares; });
  long over = 0;
  std::string over_names;
  for (const std::string& p : runs.order) {
    const auto& levels = runs.by_particle.at(p);
    const auto it = levels.find(kFine);
    if (it == levels.end() || !(it->second.cpu > kBudgetSeconds)) continue;
    over_names += (over++ ? ";" : "") + p;
  }
  // The exponent 100 → 1000's columns, then the least-squares slope's ("fit_").
  std::vector<std::string> header = {"particles", "high_exponent", "budget_seconds"};
  for (const char* of : {"exponent_", "fit_"}) {
    for (const char* what : {"particles", "median", "min", "max", "max_particle", "above_high"})
      header.push_back(std::string(of) + what);
  }
  header.insert(header.end(), {"over_budget", "over_budget_particles"});
  asperity::io::CsvWriter csv(header, 17);
  csv.number(static_cast<double>(runs.order.size())).number(kHighExponent).number(kBudgetSeconds);
  for (const Spread& s : {e, f}) {
    csv.number(static_cast<double>(s.particles))
        .number(s.median)
        .number(s.least)
        .number(s.largest)
        .field(s.largest_particle)
        .number(static_cast<double>(s.above_high));
  }
  csv.number(static_cast<double>(over)).field(over_names).end_row();
  return csv.str();
}

std::string exponent_bins(const std::vector<Exponents>& es) {
  std::map<long, long> bins;  // b → count in [b/10, (b + 1)/10)
  // 1e-9: an exponent that is a tenth to round-off (1.2 computed as 1.19999...) falls in its own.
  for (const Exponents& e : es)
    if (!std::isnan(e.exponent)) ++bins[std::lround(std::floor(e.exponent * 10 + 1e-9))];
  asperity::io::CsvWriter csv({"bin_low", "bin_high", "particles"}, 17);
  for (const auto& [b, n] : bins) {
    csv.number(static_cast<double>(b) / 10)
        .number(static_cast<double>(b + 1) / 10)
        .number(static_cast<double>(n))
        .end_row();
  }
  return csv.str();
}

}  // namespace

int main(int argc, char** argv) {
  return asperity::io::table_program(argc, argv, 2, "collision_cost RUNS.csv OUT_DIR", [&] {
    const Runs runs = read_runs(argv[1]);
    const std::vector<Exponents> es = exponents(runs);
    const std::filesystem::path out = argv[2];
    std::filesystem::create_directories(out);
    asperity::io::write_atomically(out / "by_faces.csv", by_faces(runs));
    asperity::io::write_atomically(out / "by_particle.csv", by_particle(es));
    asperity::io::write_atomically(out / "summary.csv", summary(runs, es));
    asperity::io::write_atomically(out / "exponent_bins.csv", exponent_bins(es));
  });
}
