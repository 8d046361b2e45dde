// `asperity report DIR`: the particle-geometry study's report (Markdown + HTML with matplotlib
// charts) from the tables `asperity study` wrote, by tools/report/study_report.py.
#include <spawn.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "app/out_folder.hpp"
#include "solver/core/error.hpp"

extern char** environ;

namespace asperity::app {
namespace {
namespace fs = std::filesystem;

// The script ships in the source tree; the build records where (solver/CMakeLists.txt).
const char* const kReportScript = ASPERITY_REPORT_SCRIPT;
// Debian's interpreter, which has python3-matplotlib (a python3 earlier on PATH may not).
const char* const kPython = "/usr/bin/python3";

int run_process(const std::vector<std::string>& argv) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, args[0], nullptr, nullptr, args.data(), environ) != 0) {
    throw std::runtime_error("cannot start " + argv[0]);
  }
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) throw std::runtime_error("lost " + argv[0]);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

// `asperity report`: its name and its help paragraph.
constexpr CommandText kReport{
    .name = "report",
    .about =
        "Report of a study folder (asperity study): OUT/report.md, "
        "OUT/report.html, charts (PNG) and the tables "
        "(CSV); adds the stability sweep, the YADE comparison and the penalty sensitivity "
        "(reports/study/penalty/) when present",
};

struct ReportArgs {
  fs::path study, out, stability, yade;
  std::string python = kPython;
};

int report(const ReportArgs& a) {
  if (!fs::exists(a.study / "cases.csv") || !fs::exists(a.study / "study_summary.json")) {
    throw InputError(a.study.string() +
                     ": not a study folder (no cases.csv / study_summary.json; run "
                     "asperity study first)");
  }
  if (!a.stability.empty() && !fs::is_directory(a.stability)) {
    throw InputError("--stability: " + a.stability.string() + ": no such folder");
  }
  if (!fs::exists(a.python)) throw InputError("--python: " + a.python + ": no such program");
  if (!fs::exists(kReportScript)) {
    throw std::runtime_error(std::string("report script ") + kReportScript +
                             " is missing (source tree moved?)");
  }
  const fs::path out = a.out.empty() ? a.study : a.out;
  check_out_folder(out);
  fs::path stability = a.stability;
  // The script is ROOT/tools/report/study_report.py; the reports are ROOT/reports.
  const fs::path reports =
      fs::path(kReportScript).parent_path().parent_path().parent_path() / "reports";
  if (stability.empty() && fs::is_directory(a.study / "stability"))
    stability = a.study / "stability";
  if (stability.empty() && fs::is_directory(reports / "stability"))
    stability = reports / "stability";
  fs::path yade = a.yade;
  const fs::path default_yade = reports / "yade";
  if (yade.empty() && fs::exists(default_yade)) yade = default_yade;
  std::vector<std::string> argv = {a.python, kReportScript, a.study.string(), "--out",
                                   out.string()};
  if (!stability.empty()) argv.insert(argv.end(), {"--stability", stability.string()});
  if (!yade.empty()) argv.insert(argv.end(), {"--yade", yade.string()});
  // The penalty-sensitivity runs (tools/report/penalty_sensitivity.sh), when present.
  const fs::path penalty = reports / "study" / "penalty";
  if (fs::exists(penalty / "penalty_sensitivity.csv")) {
    argv.insert(argv.end(), {"--penalty", penalty.string()});
  }
  const int rc = run_process(argv);
  // The script checks its inputs before writing anything; exit 2 is bad input, already
  // reported on one line naming the file.
  if (rc == kExitBadInput) return kExitBadInput;
  if (rc != 0) throw std::runtime_error("report script failed (exit " + std::to_string(rc) + ")");
  std::fprintf(stderr, "report -> %s, %s\n", (out / "report.md").string().c_str(),
               (out / "report.html").string().c_str());
  return kExitOk;
}

}  // namespace

void add_report_command(CLI::App& app, Action& action) {
  const auto [cmd, args] = add_command<ReportArgs>(app, action, kReport, report);
  cmd->add_option("study", args->study, "Study folder (as asperity study --out wrote it)")
      ->required();
  cmd->add_option("--out", args->out, "Report folder (default: the study folder)");
  cmd->add_option("--stability", args->stability,
                  "A folder of stability sweeps (stability.csv or map.csv, in it or one level "
                  "down; default: STUDY/stability, else reports/stability/, when present)");
  cmd->add_option(
      "--yade", args->yade,
      "Folder of YADE cross-checks (comparison.json files; default: reports/yade/ when present)");
  cmd->add_option("--python", args->python, "Python with matplotlib")->capture_default_str();
}

}  // namespace asperity::app
