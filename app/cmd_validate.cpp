// `asperity validate CASES... --out DIR`: run validation cases, check them, write the report.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>

#include "app/commands.hpp"
#include "app/out_folder.hpp"
#include "case.hpp"
#include "cluster/task_pool.hpp"
#include "core/error.hpp"
#include "junit.hpp"
#include "peers/external_solver.hpp"
#include "peers/peer.hpp"
#include "run/run_scene.hpp"
#include "run/stability_sweep.hpp"

namespace asperity::app {
namespace {
namespace fs = std::filesystem;

std::string csv_escape(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string o = "\"";
  for (char c : s) o += c == '"' ? std::string("\"\"") : std::string(1, c);
  return o + "\"";
}

// The case run by asperity (its outputs written) or by the solver (it wrote them); a solver that
// fails fails the case, with its one-line reason on stderr.
validation::CaseResult solve(const validation::CaseDef& c, const peers::CaseSolver& solver,
                             const fs::path& dir) {
  if (!solver.any()) {
    validation::CaseResult r = validation::run_case(c);
    if (r.sweep) {
      run::write_stability(*r.sweep, dir);
    } else {
      run::write_outputs(r.run, dir);
    }
    return r;
  }
  try {
    return validation::check_case(c, peers::solve_case(solver, c, dir));
  } catch (const peers::PeerFailure& e) {
    std::fprintf(stderr, "asperity: %s\n", e.what());
    return validation::failed_case(c, e.what());
  }
}

std::vector<validation::JUnitCase> junit_cases(const validation::CaseResult& r) {
  std::vector<validation::JUnitCase> out;
  const double cpu = r.run.summary.is_object() ? r.run.summary.value("cpu_seconds", 0.0) : 0.0;
  if (!r.error.empty()) {
    out.push_back({.classname = r.def.name,
                   .name = "run",
                   .seconds = cpu,
                   .error = true,
                   .message = r.error,
                   .details = r.def.file.string()});
  }
  for (const validation::CheckResult& c : r.checks) {
    out.push_back({.classname = r.def.name,
                   .name = c.check.quantity,
                   .seconds = cpu,
                   .failed = !c.passed,
                   .message = validation::check_message(c),
                   .details = c.check.why});
  }
  return out;
}

// One case: solved (by asperity, a peer or a --solver-cmd), outputs and check.json under
// DIR/cases/NAME/; the check, the run's CPU and the case's JUnit rows as the payload.
cluster::TaskReport run_one(const validation::CaseDef& def, const peers::CaseSolver& solver,
                            const fs::path& out) try {
  const fs::path dir = out / "cases" / def.name;
  const validation::CaseResult r = solve(def, solver, dir);
  fs::create_directories(dir);
  const nlohmann::ordered_json j = validation::to_json(r);
  {
    std::ofstream c(out / "cases" / r.def.name / "check.json");
    c << j.dump(2) << "\n";
  }
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const validation::JUnitCase& c : junit_cases(r)) {
    rows.push_back({{"classname", c.classname},
                    {"name", c.name},
                    {"seconds", c.seconds},
                    {"failed", c.failed},
                    {"error", c.error},
                    {"message", c.message},
                    {"details", c.details}});
  }
  const double cpu = r.run.summary.is_object() ? r.run.summary.value("cpu_seconds", 0.0) : 0.0;
  const nlohmann::ordered_json payload = {{"check", j}, {"cpu", cpu}, {"junit", rows}};
  return {.failed = !r.passed, .note = r.def.name, .payload = payload.dump()};
} catch (const std::exception& e) {
  // An error stops the command as it did before cases ran in a pool: raised again below, on
  // every rank alike.
  const bool input = dynamic_cast<const InputError*>(&e) != nullptr;
  return {.failed = true,
          .note = def.name,
          .payload = nlohmann::ordered_json{{"error", e.what()}, {"input", input}}.dump()};
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

void write_report(const std::vector<cluster::TaskReport>& reports, const fs::path& out,
                  const std::string& solved_by, bool quiet);

int cmd_validate(const std::vector<fs::path>& paths, const fs::path& out, int jobs,
                 const peers::CaseSolver& solver, const std::optional<fs::path>& junit,
                 bool quiet) {
  std::vector<fs::path> files;
  for (const fs::path& p : paths) {
    for (const fs::path& f : validation::find_cases(p)) files.push_back(f);
  }
  // Load every case first: a bad case file is bad input, reported before anything runs.
  std::vector<validation::CaseDef> cases;
  for (const fs::path& f : files) cases.push_back(validation::load_case(f));
  // Each case writes into DIR/cases/NAME: two cases of one name would overwrite one folder.
  std::map<std::string, fs::path> seen;
  for (const validation::CaseDef& c : cases) {
    const auto [it, fresh] = seen.emplace(c.name, c.file);
    if (!fresh) {
      throw InputError(c.file.string() + ": case: \"" + c.name + "\" is also the name of " +
                       it->second.string() + " (each case writes into a folder of its name)");
    }
  }
  check_out_folder(out);
  if (solver.any()) peers::check_solver(solver, cases);
  if (junit) fs::remove(*junit);
  const std::string solved_by = solver.external() ? "the command `" + solver.command + "`"
                                : solver.any()    ? "the peer " + solver.peer
                                                  : "asperity";

  cluster::World world;
  return world.guard([&] {
    if (world.root()) fs::create_directories(out / "cases");
    // Each case on whichever rank's worker is free (cases in their order: they cost about the
    // same); its outputs on disk, its check back to rank 0 as the report's payload.
    std::vector<int> order(cases.size());
    for (std::size_t k = 0; k < cases.size(); ++k) order[k] = static_cast<int>(k);
    const auto t0 = std::chrono::steady_clock::now();
    int reported = 0;
    const std::vector<cluster::TaskReport> reports = cluster::run_tasks(
        world, static_cast<int>(cases.size()), order, jobs,
        [&](int k) { return run_one(cases[static_cast<std::size_t>(k)], solver, out); },
        [&](const cluster::TaskReport& r, int) {
          ++reported;
          if (quiet) return;
          const nlohmann::ordered_json p = nlohmann::ordered_json::parse(r.payload);
          if (p.contains("error")) return;
          const nlohmann::ordered_json& j = p["check"];
          const double el =
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          std::fprintf(stderr, "[%d/%zu] %-48s %s  (%.2f s CPU; %.0f s elapsed)\n", reported,
                       cases.size(), j["case"].get<std::string>().c_str(),
                       j["passed"].get<bool>() ? "pass" : "FAIL", p["cpu"].get<double>(), el);
          if (!j["passed"].get<bool>()) {
            for (const auto& c : j["checks"]) {
              if (!c["passed"].get<bool>()) {
                std::fprintf(stderr, "    %s: expected %s, got %s\n",
                             c["quantity"].get<std::string>().c_str(), c["expected"].dump().c_str(),
                             c["got"].dump().c_str());
              }
            }
          }
        });
    rethrow_errors(reports);
    int failed = 0;
    for (const cluster::TaskReport& r : reports) failed += r.failed ? 1 : 0;
    if (world.root()) {
      write_report(reports, out, solved_by, quiet);
      if (junit) {
        std::vector<validation::JUnitCase> rows;
        for (const cluster::TaskReport& r : reports) {
          const nlohmann::json p = nlohmann::json::parse(r.payload);
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
        validation::write_junit(*junit, "asperity validate (" + solved_by + ")", rows);
      }
    }
    return failed == 0 ? kExitOk : kExitFailure;
  });
}

// DIR/results.csv, report.md and validation.json from every case's check, in the cases' order.
void write_report(const std::vector<cluster::TaskReport>& reports, const fs::path& out,
                  const std::string& solved_by, bool quiet) {
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  std::ostringstream csv, md;
  csv << "case,quantity,reference,expected,got,rel_error,rel_tol,abs_tol,passed,cpu_seconds\n";
  int failed = 0;
  double cpu_total = 0;
  for (const cluster::TaskReport& r : reports) {
    const nlohmann::ordered_json p = nlohmann::ordered_json::parse(r.payload);
    const nlohmann::ordered_json& j = p["check"];
    const double cpu = p["cpu"].get<double>();
    cpu_total += cpu;
    if (!j["passed"].get<bool>()) ++failed;
    for (const auto& c : j["checks"]) {
      csv << csv_escape(j["case"].get<std::string>()) << ',' << c["quantity"].get<std::string>()
          << ',' << c["reference"].get<std::string>() << ',' << c["expected"].dump() << ','
          << c["got"].dump() << ',' << (c.contains("rel_error") ? c["rel_error"].dump() : "") << ','
          << (c.contains("rel_tol") ? c["rel_tol"].dump() : "") << ','
          << (c.contains("abs_tol") ? c["abs_tol"].dump() : "") << ','
          << (c["passed"].get<bool>() ? "true" : "false") << ',' << cpu << '\n';
    }
    all.push_back(j);
  }
  const std::size_t n = reports.size();
  md << "# asperity validation report\n\n"
     << "Solved by " << solved_by << ".\n\n"
     << n - failed << " of " << n << " cases pass; " << cpu_total << " s CPU in all.\n\n"
     << "Each case is a scene plus expected values (`validation/cases/`). `rel error` is "
        "(got − expected)/|expected|; a check passes when |got − expected| ≤ rel_tol·|expected| + "
        "abs_tol, or within its max/min bound.\n\n"
     << "| case | quantity | reference | expected | got | rel error | tolerance | pass |\n"
     << "|---|---|---|---|---|---|---|---|\n";
  for (const auto& j : all) {
    for (const auto& c : j["checks"]) {
      std::string tol;
      if (c.contains("rel_tol")) {
        std::ostringstream t;
        t << c["rel_tol"].get<double>() << " rel";
        if (c["abs_tol"].get<double>() != 0) t << " + " << c["abs_tol"].get<double>() << " abs";
        tol = t.str();
      } else {
        const std::string ref = c["reference"].get<std::string>();
        tol = ref == "max"     ? "≤ expected"
              : ref == "min"   ? "≥ expected"
              : ref == "range" ? "≤ " + c["upper"].dump()
                               : "equal";
      }
      std::ostringstream err;
      if (c.contains("rel_error") && c["rel_error"].is_number())
        err.precision(3), err << c["rel_error"].get<double>();
      md << "| " << j["case"].get<std::string>() << " | " << c["quantity"].get<std::string>()
         << " | " << c["reference"].get<std::string>() << " | " << c["expected"].dump() << " | "
         << c["got"].dump() << " | " << err.str() << " | " << tol << " | "
         << (c["passed"].get<bool>() ? "yes" : "**NO**") << " |\n";
    }
  }
  std::ofstream(out / "results.csv") << csv.str();
  std::ofstream(out / "report.md") << md.str();
  nlohmann::ordered_json summary;
  summary["solver"] = solved_by;
  summary["cases"] = n;
  summary["passed"] = n - failed;
  summary["failed"] = failed;
  summary["cpu_seconds"] = cpu_total;
  summary["results"] = all;
  std::ofstream(out / "validation.json") << summary.dump(2) << "\n";
  if (!quiet) {
    std::fprintf(stderr, "%zu of %zu cases pass -> %s\n", n - failed, n,
                 (out / "report.md").string().c_str());
  }
}

}  // namespace

void add_validate_command(CLI::App& app, Action& action) {
  struct Args {
    std::vector<fs::path> cases;
    fs::path out;
    int jobs = 1;
    peers::CaseSolver solver;
    std::optional<fs::path> junit;
    bool quiet = false;
  };
  auto args = std::make_shared<Args>();
  auto* validate = app.add_subcommand(
      "validate",
      "Run validation cases (files or folders of case JSON) and check them: writes "
      "DIR/report.md, DIR/results.csv, DIR/validation.json, DIR/cases/NAME/. Under mpirun or srun "
      "the cases are spread over the ranks (docs/cluster.md)");
  validate->add_option("cases", args->cases, "Case files or folders")->required();
  validate->add_option("--out", args->out, "Output folder")->required();
  validate->add_option("-j,--jobs", args->jobs, "Worker threads per process (default 1)")
      ->check(CLI::PositiveNumber);
  std::string names;
  for (const peers::Adapter& a : peers::adapters())
    names += std::string(names.empty() ? "" : "|") + a.name;
  validate->add_option("--solver", args->solver.peer,
                       "Solve the cases with a peer (" + names +
                           ") at asperity's step, and gate it (docs/crosscheck.md)");
  validate->add_option("--solver-program", args->solver.program,
                       "The --solver peer's executable (default: its program on PATH)");
  validate->add_option("--solver-cmd", args->solver.command,
                       "Solve the cases with any program that honours the contract: a shell "
                       "command line where {scene} is the scene file and {out} the folder for its "
                       "summary.json and force.csv");
  validate->add_option("--junit", args->junit,
                       "Also write JUnit XML: one testcase per case and check");
  validate->add_flag("-q,--quiet", args->quiet, "Only errors on stderr");
  validate->callback([args, &action] {
    action = [args] {
      return cmd_validate(args->cases, args->out, args->jobs, args->solver, args->junit,
                          args->quiet);
    };
  });
}

}  // namespace asperity::app
