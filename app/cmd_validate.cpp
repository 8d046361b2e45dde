// `asperity validate CASES... --out DIR`: run validation cases, check them, write the report
// (validation/validate.hpp).
#include <filesystem>
#include <memory>

#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "app/out_folder.hpp"
#include "peers/external_solver.hpp"
#include "peers/peer.hpp"
#include "solver/core/error.hpp"
#include "validation/validate.hpp"

namespace asperity::app {
namespace fs = std::filesystem;

namespace {

// `asperity validate`: its name and its help paragraph.
constexpr CommandText kValidate{
    .name = "validate",
    .about =
        "Run validation cases (files or folders of case JSON) and check them: writes "
        "DIR/report.md, DIR/results.csv, DIR/validation.json, DIR/cases/NAME/. Under mpirun or "
        "srun "
        "the cases are spread over the ranks (docs/cluster.md)",
};

struct ValidateArgs {
  std::vector<fs::path> cases;
  validation::ValidateOptions options;
  peers::CaseSolver solver;  // none: asperity solves
};

int run_cases(const ValidateArgs& a) {
  // A bad case file, then a bad --out or --junit, is exit 2 before anything runs.
  const std::vector<validation::CaseDef> cases = validation::load_cases(a.cases);
  check_out_folder(a.options.out);
  if (a.options.junit) check_out_file(*a.options.junit, "--junit");
  // A solver that cannot run them is exit 2 before anything runs or is written.
  validation::ValidateOptions options = a.options;
  if (a.solver.any()) {
    peers::check_solver(a.solver, cases);
    options.solver = peers::other_solver(a.solver);
  }
  return validation::validate_cases(cases, options) == 0 ? kExitOk : kExitFailure;
}

}  // namespace

void add_validate_command(CLI::App& app, Action& action) {
  const auto [validate, args] = add_command<ValidateArgs>(app, action, kValidate, run_cases);
  validation::ValidateOptions& o = args->options;
  peers::CaseSolver& solver = args->solver;
  validate->add_option("cases", args->cases, "Case files or folders")->required();
  add_out_folder(*validate, o.out);
  validate->add_option("-j,--jobs", o.jobs, "Worker threads per process (default 1)")
      ->check(CLI::PositiveNumber);
  validate->add_option("--solver", solver.peer,
                       "Solve the cases with a peer (" + peers::adapter_names("|") +
                           ") at asperity's step, and gate it (docs/crosscheck.md)");
  validate->add_option("--solver-program", solver.program,
                       "The --solver peer's executable (default: its program on PATH)");
  validate->add_option("--solver-cmd", solver.command,
                       "Solve the cases with any program that honours the contract: a shell "
                       "command line where {scene} is the scene file and {out} the folder for its "
                       "summary.json and force.csv");
  validate->add_option("--junit", o.junit, "Also write JUnit XML: one testcase per case and check");
  add_quiet(*validate, o.quiet, "Only errors on stderr");
}

}  // namespace asperity::app
