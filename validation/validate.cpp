// `asperity validate`'s work (validate.hpp).
#include "validation/validate.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <set>
#include <system_error>
#include <utility>
#include <variant>

#include "cluster/task_pool.hpp"
#include "cluster/world.hpp"
#include "solver/core/error.hpp"
#include "solver/io/atomic_file.hpp"
#include "solver/run/prepared_meshes.hpp"
#include "solver/run/run_scene.hpp"
#include "solver/run/stability_sweep.hpp"
#include "validation/junit.hpp"
#include "validation/validate_report.hpp"

namespace asperity::validation {
namespace {
namespace fs = std::filesystem;
using OJson = nlohmann::ordered_json;

// The case run by asperity (its outputs written) or by the other solver (it wrote them).
CaseResult solve(const CaseDef& c, const std::optional<OtherSolver>& solver, const fs::path& dir) {
  if (solver) return solver->solve(c, dir);
  CaseResult r = run_case(c);
  if (r.sweep) {
    run::write_stability(*r.sweep, dir);
  } else {
    run::write_outputs(r.run, dir);
  }
  return r;
}

double cpu_of(const CaseResult& r) {
  return r.run.summary.is_object() ? r.run.summary.value("cpu_seconds", 0.0) : 0.0;
}

// The case's JUnit rows: an error row when the run failed, one row a check.
OJson junit_rows(const CaseResult& r) {
  std::vector<JUnitCase> rows;
  if (!r.error.empty()) {
    rows.push_back({.classname = r.def.name,
                    .name = "run",
                    .seconds = cpu_of(r),
                    .error = true,
                    .message = r.error,
                    .details = r.def.file.string()});
  }
  for (const CheckResult& c : r.checks) {
    rows.push_back({.classname = r.def.name,
                    .name = c.check.quantity,
                    .seconds = cpu_of(r),
                    .failed = !c.passed,
                    .message = check_message(c),
                    .details = c.check.why});
  }
  OJson out = OJson::array();
  for (const JUnitCase& c : rows) {
    out.push_back({{"classname", c.classname},
                   {"name", c.name},
                   {"seconds", c.seconds},
                   {"failed", c.failed},
                   {"error", c.error},
                   {"message", c.message},
                   {"details", c.details}});
  }
  return out;
}

// One case: solved, outputs and check.json under DIR/cases/NAME/; the check, the run's CPU and
// the case's JUnit rows as the payload.
cluster::TaskReport run_one(const CaseDef& def, const std::optional<OtherSolver>& solver,
                            const fs::path& out) try {
  const fs::path dir = out / "cases" / def.name;
  const CaseResult r = solve(def, solver, dir);
  fs::create_directories(dir);
  const OJson j = to_json(r);
  io::write_atomically(dir / "check.json", j.dump(2) + "\n");
  const OJson payload = {{"check", j}, {"cpu", cpu_of(r)}, {"junit", junit_rows(r)}};
  return {.failed = !r.passed, .note = r.def.name, .payload = payload.dump()};
} catch (const std::exception& e) {
  // An error stops the command as it did before cases ran in a pool: raised again below, on
  // every rank alike.
  const bool input = dynamic_cast<const InputError*>(&e) != nullptr;
  return {.failed = true,
          .note = def.name,
          .payload = OJson{{"error", e.what()}, {"input", input}}.dump()};
}

// The order the cases are handed out in. Meshing a body's file is most of a validation's time
// (7 s for the 2000-vertex hull, against 0.02 s of stepping), and a process keeps the meshes it
// has made (run/prepared_meshes.hpp): first the cases that mesh something no earlier case
// meshes, the largest file first; then the cases without mesh bodies, in their order; last the
// cases whose meshes are made by then, so that no worker waits for a mesh another is still making.
std::vector<int> case_order(const std::vector<CaseDef>& cases) {
  std::vector<std::pair<std::uintmax_t, int>> first;  // (bytes of new mesh files, case)
  std::vector<int> plain, again;
  std::set<std::pair<std::string, run::MeshKey>> meshed;  // (file named, not read; its keys)
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const scene::SceneDef& s = cases[k].scene;
    std::uintmax_t bytes = 0;
    bool mesh = false;
    for (const scene::BodyDef& b : s.bodies) {
      const auto* m = std::get_if<scene::MeshShape>(&b.shape);
      if (!m) continue;
      mesh = true;
      if (!meshed
               .emplace(m->file.lexically_normal().string(),
                        run::mesh_key(*m, b.model == scene::Model::fem && !b.fixed))
               .second) {
        continue;
      }
      std::error_code ec;
      const std::uintmax_t size = fs::file_size(m->file, ec);
      bytes += ec ? 0 : size;
    }
    const int i = static_cast<int>(k);
    if (!mesh) {
      plain.push_back(i);
    } else if (bytes > 0) {
      first.emplace_back(bytes, i);
    } else {
      again.push_back(i);
    }
  }
  std::stable_sort(first.begin(), first.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<int> order;
  for (const auto& [bytes, i] : first) order.push_back(i);
  order.insert(order.end(), plain.begin(), plain.end());
  order.insert(order.end(), again.begin(), again.end());
  return order;
}

// The first case that raised an error raises it again (every rank holds every report).
void rethrow_errors(const std::vector<cluster::TaskReport>& reports) {
  for (const cluster::TaskReport& r : reports) {
    const nlohmann::json p = nlohmann::json::parse(r.payload);
    if (!p.contains("error")) continue;
    if (p["input"].get<bool>()) throw InputError(p["error"].get<std::string>());
    throw std::runtime_error(p["error"].get<std::string>());
  }
}

// A finished case on stderr: pass or FAIL, its CPU, and each missed check.
void print_progress(const OJson& p, int reported, std::size_t total, double elapsed) {
  const OJson& j = p["check"];
  std::fprintf(stderr, "[%d/%zu] %-48s %s  (%.2f s CPU; %.0f s elapsed)\n", reported, total,
               j["case"].get<std::string>().c_str(), j["passed"].get<bool>() ? "pass" : "FAIL",
               p["cpu"].get<double>(), elapsed);
  if (j["passed"].get<bool>()) return;
  for (const auto& c : j["checks"]) {
    if (!c["passed"].get<bool>()) {
      std::fprintf(stderr, "    %s: expected %s, got %s\n",
                   c["quantity"].get<std::string>().c_str(), c["expected"].dump().c_str(),
                   c["got"].dump().c_str());
    }
  }
}

// Rank 0: the report and, when asked, the JUnit XML, from every case's payload.
void write_results(const std::vector<cluster::TaskReport>& reports, const ValidateOptions& o,
                   const std::string& solved_by) {
  std::vector<CaseOutcome> cases;
  std::vector<JUnitCase> rows;
  for (const cluster::TaskReport& r : reports) {
    const OJson p = OJson::parse(r.payload);
    cases.push_back({.check = p["check"], .cpu_seconds = p["cpu"].get<double>()});
    for (const auto& c : p["junit"]) {
      rows.push_back({.classname = c["classname"].get<std::string>(),
                      .name = c["name"].get<std::string>(),
                      .seconds = c["seconds"].get<double>(),
                      .failed = c["failed"].get<bool>(),
                      .error = c["error"].get<bool>(),
                      .message = c["message"].get<std::string>(),
                      .details = c["details"].get<std::string>()});
    }
  }
  write_validate_report(cases, o.out, solved_by);
  if (o.junit) write_junit(*o.junit, "asperity validate (" + solved_by + ")", rows);
}

}  // namespace

std::vector<CaseDef> load_cases(const std::vector<fs::path>& paths) {
  std::vector<CaseDef> cases;
  for (const fs::path& p : paths) {
    for (const fs::path& f : find_cases(p)) cases.push_back(load_case(f));
  }
  std::map<std::string, fs::path> seen;
  for (const CaseDef& c : cases) {
    const auto [it, fresh] = seen.emplace(c.name, c.file);
    if (!fresh) {
      throw InputError(c.file.string() + ": case: \"" + c.name + "\" is also the name of " +
                       it->second.string() + " (each case writes into a folder of its name)");
    }
  }
  return cases;
}

int validate_cases(const std::vector<CaseDef>& cases, const ValidateOptions& o) {
  if (o.junit) io::remove_earlier_output(*o.junit);
  const std::string solved_by = o.solver ? o.solver->name : "asperity";
  cluster::World world;
  return world.guard([&] {
    if (world.root()) fs::create_directories(o.out / "cases");
    // Each case on whichever rank's worker is free, in case_order; its outputs on disk, its
    // check back to rank 0 as the report's payload.
    const std::vector<int> order = case_order(cases);
    const auto t0 = std::chrono::steady_clock::now();
    int reported = 0;
    const std::vector<cluster::TaskReport> reports = cluster::run_tasks(
        world, static_cast<int>(cases.size()), order, o.jobs,
        [&](int k) { return run_one(cases[static_cast<std::size_t>(k)], o.solver, o.out); },
        [&](const cluster::TaskReport& r, int) {
          ++reported;
          if (o.quiet) return;
          const OJson p = OJson::parse(r.payload);
          if (p.contains("error")) return;
          print_progress(
              p, reported, cases.size(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        });
    rethrow_errors(reports);
    int failed = 0;
    for (const cluster::TaskReport& r : reports) failed += r.failed ? 1 : 0;
    if (world.root()) {
      write_results(reports, o, solved_by);
      if (!o.quiet) {
        std::fprintf(stderr, "%zu of %zu cases pass -> %s\n",
                     cases.size() - static_cast<std::size_t>(failed), cases.size(),
                     (o.out / "report.md").string().c_str());
      }
    }
    return failed;
  });
}

}  // namespace asperity::validation
