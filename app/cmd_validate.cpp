// `asperity validate CASES... --out DIR [--solver PEER | --solver-cmd 'PROGRAM {scene} {out}']
// [--junit FILE]`: run validation cases (in asperity, a peer, or any contract-honouring program),
// check them, write the report.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>

#include "app/commands.hpp"
#include "case.hpp"
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

int cmd_validate(const std::vector<fs::path>& paths, const fs::path& out,
                 const peers::CaseSolver& solver, const std::optional<fs::path>& junit,
                 bool quiet) {
  std::vector<fs::path> files;
  for (const fs::path& p : paths) {
    for (const fs::path& f : validation::find_cases(p)) files.push_back(f);
  }
  // Load every case first: a bad case file is bad input, reported before anything runs.
  std::vector<validation::CaseDef> cases;
  for (const fs::path& f : files) cases.push_back(validation::load_case(f));
  if (solver.any()) peers::check_solver(solver, cases);
  if (junit) fs::remove(*junit);
  std::vector<validation::JUnitCase> junit_rows;

  fs::create_directories(out / "cases");
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  std::ostringstream csv, md;
  csv << "case,quantity,reference,expected,got,rel_error,rel_tol,abs_tol,passed,cpu_seconds\n";
  int failed = 0;
  double cpu_total = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const validation::CaseResult r = solve(cases[k], solver, out / "cases" / cases[k].name);
    for (auto& row : junit_cases(r)) junit_rows.push_back(std::move(row));
    const nlohmann::ordered_json j = validation::to_json(r);
    fs::create_directories(out / "cases" / r.def.name);
    {
      std::ofstream c(out / "cases" / r.def.name / "check.json");
      c << j.dump(2) << "\n";
    }
    all.push_back(j);
    const double cpu = r.run.summary.is_object() ? r.run.summary.value("cpu_seconds", 0.0) : 0.0;
    cpu_total += cpu;
    if (!r.passed) ++failed;
    for (const auto& c : j["checks"]) {
      csv << csv_escape(r.def.name) << ',' << c["quantity"].get<std::string>() << ','
          << c["reference"].get<std::string>() << ',' << c["expected"].dump() << ','
          << c["got"].dump() << ',' << (c.contains("rel_error") ? c["rel_error"].dump() : "") << ','
          << (c.contains("rel_tol") ? c["rel_tol"].dump() : "") << ','
          << (c.contains("abs_tol") ? c["abs_tol"].dump() : "") << ','
          << (c["passed"].get<bool>() ? "true" : "false") << ',' << cpu << '\n';
    }
    if (!quiet) {
      const double el =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::fprintf(stderr, "[%zu/%zu] %-48s %s  (%.2f s CPU; %.0f s elapsed)\n", k + 1,
                   cases.size(), r.def.name.c_str(), r.passed ? "pass" : "FAIL", cpu, el);
      for (const validation::CheckResult& c : r.checks) {
        if (!c.passed) std::fprintf(stderr, "    %s\n", validation::check_message(c).c_str());
      }
    }
  }
  const std::string solved_by = solver.external() ? "the command `" + solver.command + "`"
                                : solver.any()    ? "the peer " + solver.peer
                                                  : "asperity";
  md << "# asperity validation report\n\n"
     << "Solved by " << solved_by << ".\n\n"
     << cases.size() - failed << " of " << cases.size() << " cases pass; " << cpu_total
     << " s CPU in all.\n\n"
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
  summary["solver"] = solver.external() ? "command: " + solver.command
                      : solver.any()    ? solver.peer
                                        : "asperity";
  summary["cases"] = cases.size();
  summary["passed"] = cases.size() - failed;
  summary["failed"] = failed;
  summary["cpu_seconds"] = cpu_total;
  summary["results"] = all;
  std::ofstream(out / "validation.json") << summary.dump(2) << "\n";
  if (junit) validation::write_junit(*junit, "asperity validate (" + solved_by + ")", junit_rows);
  if (!quiet) {
    std::fprintf(stderr, "%zu of %zu cases pass -> %s\n", cases.size() - failed, cases.size(),
                 (out / "report.md").string().c_str());
  }
  return failed == 0 ? kExitOk : kExitFailure;
}

}  // namespace

void add_validate_command(CLI::App& app, Action& action) {
  struct Args {
    std::vector<fs::path> cases;
    fs::path out;
    peers::CaseSolver solver;
    std::optional<fs::path> junit;
    bool quiet = false;
  };
  auto args = std::make_shared<Args>();
  auto* validate = app.add_subcommand(
      "validate",
      "Run validation cases (files or folders of case JSON) and check them: writes "
      "DIR/report.md, DIR/results.csv, DIR/validation.json, DIR/cases/NAME/. With --solver or "
      "--solver-cmd another code solves the cases and is gated on the same expectations");
  validate->add_option("cases", args->cases, "Case files or folders")->required();
  validate->add_option("--out", args->out, "Output folder")->required();
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
      return cmd_validate(args->cases, args->out, args->solver, args->junit, args->quiet);
    };
  });
}

}  // namespace asperity::app
