// A validation case: one scene plus expected values with tolerances and their reasons.
// The same file feeds the ctest gate, the validation report and the YADE cross-check.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/run/run_scene.hpp"
#include "solver/run/stability_sweep.hpp"
#include "solver/scene/scene.hpp"

namespace asperity::validation {

// One expectation on a summary.json quantity.
struct Check {
  std::string quantity;   // a summary.json key, e.g. "peak_force"
  std::string reference;  // "value", "hertz", "target_restitution", "max", "min", "range", "equals"
  double expected = 0;    // resolved reference value (the lower bound for "range")
  double upper = 0;       // the upper bound for "range"
  double rel_tol = 0;     // |got − expected| ≤ rel_tol·|expected| + abs_tol
  double abs_tol = 0;
  std::string why;   // the tolerance's reason (and the reference's source)
  std::string text;  // for "equals" (status)
};

struct CaseDef {
  std::filesystem::path file;
  std::string name;
  std::string description;
  std::vector<std::string> tags;
  scene::SceneDef scene;
  // A stability case sweeps the step (run/stability_sweep.hpp) and checks the sweep's summary.
  std::optional<std::vector<double>> sweep_factors;
  std::optional<double> sweep_reference_factor;
  std::vector<Check> checks;
};

struct CheckResult {
  Check check;
  double got = 0;
  std::string got_text;
  bool passed = false;
};

struct CaseResult {
  CaseDef def;
  run::RunResult run;                         // a sweep case: its summary is the sweep's
  std::optional<run::StabilityResult> sweep;  // set for a sweep case
  std::vector<CheckResult> checks;
  bool passed = false;
  std::string error;  // the solver failed (a peer or --solver-cmd): why; no checks then
};

// What is wrong with a case name as a folder name under --out ("" when nothing): empty, "." or
// "..", a path separator, control characters, over 200 characters.
std::string case_name_problem(const std::string& name);

// Reads a case; resolves analytic references from its scene. Throws InputError.
CaseDef load_case(const std::filesystem::path& file);

// Case files under a path (a file, or a folder searched recursively), sorted.
std::vector<std::filesystem::path> find_cases(const std::filesystem::path& path);

CaseResult run_case(const CaseDef& def);

// Checks a run of the case's scene (by asperity, a peer or an external solver) against the case's
// expectations.
CaseResult check_case(const CaseDef& def, run::RunResult run);

// A case whose solver failed: no checks, not passed, `error` says why.
CaseResult failed_case(const CaseDef& def, const std::string& error);

// One line per check that failed: "quantity: got G, expected E (rel error R, tolerance T)".
std::string check_message(const CheckResult& c);

nlohmann::ordered_json to_json(const CaseResult& r);

}  // namespace asperity::validation
