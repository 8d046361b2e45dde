// `asperity validate CASES... --out DIR`: run validation cases, check them, write the report
// (validation/validate.hpp).
#include <filesystem>
#include <memory>

#include "app/commands.hpp"
#include "app/out_folder.hpp"
#include "peers/external_solver.hpp"
#include "peers/peer.hpp"
#include "solver/core/error.hpp"
#include "validation/validate.hpp"

namespace asperity::app {
namespace fs = std::filesystem;

void add_validate_command(CLI::App& app, Action& action) {
  struct Args {
    std::vector<fs::path> cases;
    validation::ValidateOptions options;
    peers::CaseSolver solver;  // none: asperity solves
  };
  auto args = std::make_shared<Args>();
  validation::ValidateOptions& o = args->options;
  peers::CaseSolver& solver = args->solver;
  auto* validate = app.add_subcommand(
      "validate",
      "Run validation cases (files or folders of case JSON) and check them: writes "
      "DIR/report.md, DIR/results.csv, DIR/validation.json, DIR/cases/NAME/. Under mpirun or srun "
      "the cases are spread over the ranks (docs/cluster.md)");
  validate->add_option("cases", args->cases, "Case files or folders")->required();
  validate->add_option("--out", o.out, "Output folder")->required();
  validate->add_option("-j,--jobs", o.jobs, "Worker threads per process (default 1)")
      ->check(CLI::PositiveNumber);
  std::string names;
  for (const peers::Adapter& a : peers::adapters())
    names += std::string(names.empty() ? "" : "|") + a.name;
  validate->add_option("--solver", solver.peer,
                       "Solve the cases with a peer (" + names +
                           ") at asperity's step, and gate it (docs/crosscheck.md)");
  validate->add_option("--solver-program", solver.program,
                       "The --solver peer's executable (default: its program on PATH)");
  validate->add_option("--solver-cmd", solver.command,
                       "Solve the cases with any program that honours the contract: a shell "
                       "command line where {scene} is the scene file and {out} the folder for its "
                       "summary.json and force.csv");
  validate->add_option("--junit", o.junit, "Also write JUnit XML: one testcase per case and check");
  validate->add_flag("-q,--quiet", o.quiet, "Only errors on stderr");
  validate->callback([args, &action] {
    action = [args] {
      // A bad case file, then a bad --out, is exit 2 before anything runs.
      const std::vector<validation::CaseDef> cases = validation::load_cases(args->cases);
      check_out_folder(args->options.out);
      // A solver that cannot run them is exit 2 before anything runs or is written.
      if (args->solver.any()) {
        peers::check_solver(args->solver, cases);
        args->options.solver = peers::other_solver(args->solver);
      }
      return validation::validate_cases(cases, args->options) == 0 ? kExitOk : kExitFailure;
    };
  });
}

}  // namespace asperity::app
