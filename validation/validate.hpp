// `asperity validate`'s work: the case files loaded and checked for clashes, every case solved
// (by asperity, a peer or a --solver-cmd) over the MPI task pool (cluster/task_pool.hpp), its
// outputs and check.json under DIR/cases/NAME/, and the report (validate_report.hpp) and JUnit
// XML written on rank 0.
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include "peers/external_solver.hpp"
#include "validation/case.hpp"

namespace asperity::validation {

// Every case file under `paths` (files or folders), loaded: a bad case file, or two cases of
// one name (each writes into a folder of its name), is an InputError before anything runs.
std::vector<CaseDef> load_cases(const std::vector<std::filesystem::path>& paths);

struct ValidateOptions {
  std::filesystem::path out;  // DIR: report.md, results.csv, validation.json, cases/NAME/
  int jobs = 1;               // worker threads per process
  peers::CaseSolver solver;   // none: asperity solves
  std::optional<std::filesystem::path> junit;
  bool quiet = false;  // only errors on stderr
};

// Checks the solver against the cases, then solves and checks every case and writes the
// report. Returns the number of cases that failed; an error a case raised is raised again, on
// every rank alike.
int validate_cases(const std::vector<CaseDef>& cases, const ValidateOptions& options);

}  // namespace asperity::validation
