// `asperity validate`'s work: the case files loaded and checked for clashes, every case solved
// (by asperity, a peer or a --solver-cmd) over the MPI task pool (cluster/task_pool.hpp), its
// outputs and check.json under DIR/cases/NAME/, and the report (validate_report.hpp) and JUnit
// XML written on rank 0.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "validation/case.hpp"

namespace asperity::validation {

// Every case file under `paths` (files or folders), loaded: a bad case file, or two cases of
// one name (each writes into a folder of its name), is an InputError before anything runs.
std::vector<CaseDef> load_cases(const std::vector<std::filesystem::path>& paths);

// Who solves the cases when asperity does not (a peer or a --solver-cmd: peers/external_solver.hpp
// makes one): `solve` runs a case into DIR/cases/NAME/ and checks it, a solver's failure being a
// failed case; `name` is who the report says solved them.
struct OtherSolver {
  std::string name;
  std::function<CaseResult(const CaseDef&, const std::filesystem::path& dir)> solve;
};

struct ValidateOptions {
  std::filesystem::path out;          // DIR: report.md, results.csv, validation.json, cases/NAME/
  int jobs = 1;                       // worker threads per process
  std::optional<OtherSolver> solver;  // none: asperity solves
  std::optional<std::filesystem::path> junit;
  bool quiet = false;  // only errors on stderr
};

// Solves and checks every case and writes the report. Returns the number of cases that failed; an
// error a case raised is raised again, on every rank alike.
int validate_cases(const std::vector<CaseDef>& cases, const ValidateOptions& options);

}  // namespace asperity::validation
