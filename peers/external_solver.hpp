// Who solves a validation case when it is not asperity: a peer adapter (`validate --solver PEER`)
// or any program that honours the contract (`validate --solver-cmd 'PROGRAM {scene} {out}'`):
// it reads a contract scene (docs/contract.md) and writes OUT/summary.json and OUT/force.csv.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "solver/run/run_scene.hpp"
#include "validation/case.hpp"
#include "validation/validate.hpp"

namespace asperity::peers {

struct CaseSolver {
  std::string peer;     // --solver: an adapter's name
  std::string program;  // the peer's executable (default: its own program on PATH)
  std::string command;  // --solver-cmd: a shell command line with {scene} and {out}
  bool external() const { return !command.empty(); }
  bool any() const { return !peer.empty() || !command.empty(); }
};

// Throws InputError (exit 2) before anything runs or is written: both or neither of peer and
// command, an unknown or uninstalled peer, a command without {scene} or {out}, a case the solver
// cannot run (a stability sweep; a scene the peer cannot express).
void check_solver(const CaseSolver& solver, const std::vector<validation::CaseDef>& cases);

// Runs the case's scene with the solver into `dir` (DIR/cases/NAME/): the scene as scene.json,
// the solver's summary.json and force.csv, its log. Throws PeerFailure (the case fails) when the
// solver exits non-zero or writes no readable summary.json.
run::RunResult solve_case(const CaseSolver& solver, const validation::CaseDef& c,
                          const std::filesystem::path& dir);

// The solver as `validate` takes it: each case solved (solve_case) and checked; a PeerFailure
// fails the case, with its one-line reason on stderr. Its name: "the peer NAME" or "the command
// `LINE`".
validation::OtherSolver other_solver(const CaseSolver& solver);

}  // namespace asperity::peers
