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
#include "core/error.hpp"
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

int cmd_validate(const std::vector<fs::path>& paths, const fs::path& out, bool quiet) {
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

  fs::create_directories(out / "cases");
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  std::ostringstream csv, md;
  csv << "case,quantity,reference,expected,got,rel_error,rel_tol,abs_tol,passed,cpu_seconds\n";
  int failed = 0;
  double cpu_total = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const validation::CaseResult r = validation::run_case(cases[k]);
    if (r.sweep) {
      run::write_stability(*r.sweep, out / "cases" / r.def.name);
    } else {
      run::write_outputs(r.run, out / "cases" / r.def.name);
    }
    const nlohmann::ordered_json j = validation::to_json(r);
    {
      std::ofstream c(out / "cases" / r.def.name / "check.json");
      c << j.dump(2) << "\n";
    }
    all.push_back(j);
    const double cpu = r.run.summary.value("cpu_seconds", 0.0);
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
      if (!r.passed) {
        for (const auto& c : j["checks"]) {
          if (!c["passed"].get<bool>()) {
            std::fprintf(stderr, "    %s: expected %s, got %s\n",
                         c["quantity"].get<std::string>().c_str(), c["expected"].dump().c_str(),
                         c["got"].dump().c_str());
          }
        }
      }
    }
  }
  md << "# asperity validation report\n\n"
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
  summary["cases"] = cases.size();
  summary["passed"] = cases.size() - failed;
  summary["failed"] = failed;
  summary["cpu_seconds"] = cpu_total;
  summary["results"] = all;
  std::ofstream(out / "validation.json") << summary.dump(2) << "\n";
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
    bool quiet = false;
  };
  auto args = std::make_shared<Args>();
  auto* validate = app.add_subcommand(
      "validate",
      "Run validation cases (files or folders of case JSON) and check them: writes "
      "DIR/report.md, DIR/results.csv, DIR/validation.json, DIR/cases/NAME/");
  validate->add_option("cases", args->cases, "Case files or folders")->required();
  validate->add_option("--out", args->out, "Output folder")->required();
  validate->add_flag("-q,--quiet", args->quiet, "Only errors on stderr");
  validate->callback([args, &action] {
    action = [args] { return cmd_validate(args->cases, args->out, args->quiet); };
  });
}

}  // namespace asperity::app
