// Validation cases solved by a peer or by an external contract-honouring program
// (docs/crosscheck.md, "Gating any solver").
#include "peers/external_solver.hpp"

#include <cstdio>
#include <fstream>

#include "peers/peer.hpp"
#include "solver/core/error.hpp"
#include "solver/io/atomic_file.hpp"
#include "solver/io/json_file.hpp"

namespace asperity::peers {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
  return s;
}

// force.csv as the contract writes it (t,fx,fy,fz,f); rows that do not parse end the read.
std::vector<run::ForceRow> read_force_csv(const fs::path& file) {
  std::vector<run::ForceRow> rows;
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    run::ForceRow r{};
    if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf", &r.t, &r.fx, &r.fy, &r.fz, &r.f) != 5)
      break;
    rows.push_back(r);
  }
  return rows;
}

run::RunResult run_command_solver(const std::string& command, const validation::CaseDef& c,
                                  const fs::path& dir) {
  // The scene exactly as the case file holds it.
  const io::Json cj = io::read_json_file(c.file);
  write_file(dir / "scene.json", cj.at("scene").dump(2) + "\n");
  const std::string line =
      replace_all(replace_all(command, "{scene}", shell_quote((dir / "scene.json").string())),
                  "{out}", shell_quote(dir.string()));
  const int code = run_command("( " + line + " ) > " + shell_quote((dir / "solver.log").string()) +
                               " 2>&1 < /dev/null");
  if (code != 0) {
    throw PeerFailure("--solver-cmd: exited " + std::to_string(code) + " on " + c.name + ": " +
                      log_tail(dir / "solver.log", 2) + " [log: " + (dir / "solver.log").string() +
                      "]");
  }
  if (!fs::is_regular_file(dir / "summary.json")) {
    throw PeerFailure("--solver-cmd: wrote no summary.json for " + c.name + " (in " + dir.string() +
                      "; docs/crosscheck.md gives the contract)");
  }
  run::RunResult r;
  try {
    r.summary = Json::parse(std::ifstream(dir / "summary.json"));
  } catch (const std::exception& e) {
    throw PeerFailure("--solver-cmd: " + (dir / "summary.json").string() + ": not JSON (" +
                      e.what() + ")");
  }
  if (!r.summary.is_object())
    throw PeerFailure("--solver-cmd: " + (dir / "summary.json").string() + ": not a JSON object");
  r.status = r.summary.value("status", "");
  r.force = read_force_csv(dir / "force.csv");
  return r;
}

}  // namespace

void check_solver(const CaseSolver& solver, const std::vector<validation::CaseDef>& cases) {
  if (!solver.peer.empty() && !solver.command.empty())
    throw InputError("validate: --solver and --solver-cmd: give one of them");
  if (solver.external()) {
    if (solver.command.find("{scene}") == std::string::npos ||
        solver.command.find("{out}") == std::string::npos) {
      throw InputError("validate: --solver-cmd \"" + solver.command +
                       "\": must contain {scene} and {out} (e.g. 'my_solver {scene} {out}')");
    }
  }
  const Adapter* a = nullptr;
  if (!solver.peer.empty()) {
    a = &find_adapter(solver.peer);
    peer_executable(*a, solver.program);
  }
  for (const validation::CaseDef& c : cases) {
    if (c.sweep_factors) {
      throw InputError(c.file.string() + ": sweep: a stability sweep checks asperity's own " +
                       "step predictor; --solver and --solver-cmd run single scenes");
    }
    if (a) a->check(c.scene);
  }
}

run::RunResult solve_case(const CaseSolver& solver, const validation::CaseDef& c,
                          const fs::path& dir) {
  if (solver.external()) {
    // Nothing from an earlier run may be mistaken for this one's.
    io::empty_output_folder(dir);
    return run_command_solver(solver.command, c, dir);
  }
  const Adapter& a = find_adapter(solver.peer);
  if (a.own_step) {
    return run_peer(a, peer_executable(a, solver.program), c.scene,
                    {.dt = c.scene.duration, .steps = 1}, dir);
  }
  // The peer runs at the step and step count asperity resolves for the scene (docs/crosscheck.md):
  // asperity's run here only resolves them; its results are not gated.
  const run::RunResult own = run::run_scene(c.scene, {.keep_rows = false});
  if (own.status == "unstable")
    throw PeerFailure(c.name + ": asperity's run, which resolves the step, went unstable");
  const Resolved resolved{.dt = own.summary.at("dt").get<double>(),
                          .steps = own.summary.at("steps").get<long>()};
  return run_peer(a, peer_executable(a, solver.program), c.scene, resolved, dir);
}

validation::OtherSolver other_solver(const CaseSolver& solver) {
  return {.name = solver.external() ? "the command `" + solver.command + "`"
                                    : "the peer " + solver.peer,
          .solve = [solver](const validation::CaseDef& c, const fs::path& dir) {
            try {
              return validation::check_case(c, solve_case(solver, c, dir));
            } catch (const PeerFailure& e) {
              std::fprintf(stderr, "asperity: %s\n", e.what());
              return validation::failed_case(c, e.what());
            }
          }};
}

}  // namespace asperity::peers
