// The peer-adapter interface: another DEM code (YADE, LAMMPS, LIGGGHTS) run on a contract scene
// and measured by the same code that measures asperity's own runs (docs/crosscheck.md).
//
// An adapter does three things and nothing else: it says whether the peer can express a scene
// (`check`, before anything runs or is written), turns the scene — as asperity resolved it: step,
// step count, damping of each material pair — into the peer's own input and runs the peer for
// real (`run`), and hands back what the peer recorded every step as a `PeerTrace`. Everything
// measured from that trace (peak force, impulse, contact duration, restitution, rebound) is
// measured here, once, for every peer (`measure_trace`). Adding a peer is adding one adapter file
// and one line in the table of peers.cpp.
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/core/vec.hpp"
#include "solver/run/run_scene.hpp"
#include "solver/scene/scene.hpp"

namespace asperity::peers {

// The peer ran and failed, or wrote nothing usable: exit 1 (a tool failure, not bad input).
struct PeerFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// What asperity resolved from the scene and every peer runs with.
struct Resolved {
  double dt = 0;   // s
  long steps = 0;  // steps after t = 0 (asperity's, so both stop at the same time)
};

// What a peer run is for: `trace` records every step (the cross-check's measures) after a plain
// run that gives the cost; `cost` makes the plain run alone (the cost table: no dump, no per-step
// recorder, so a 10,000-sphere scene writes nothing per step).
enum class RunMode { trace, cost };

// One sample per step, t = 0 included (empty after a RunMode::cost run). Forces are the recorded
// body's total contact force (no gravity); bodies are the scene's traced bodies in scene order
// (`traced_bodies`; fixed bodies stay where the scene puts them).
struct PeerTrace {
  std::vector<double> t;                // s
  std::vector<Vec3> force;              // N, on the recorded body
  std::vector<std::vector<Vec3>> x, v;  // [sample][traced body], m and m/s
  std::vector<Vec3> final_w;            // rad/s, each traced body's at the end
  // Set by a peer that measures the recorded body's contact itself (YADE's polyhedra, whose
  // overlap asperity does not recompute from the peer's positions), one per sample: the signed
  // depth (m; −1e300 while apart) and the unit normal into the recorded body. Empty: measured
  // from the free spheres' positions with the geometry of dem/sphere_world.cpp.
  std::vector<double> overlap;
  std::vector<Vec3> normal;
  double cpu_seconds = 0;  // the peer's engine loop alone, no recorder
  double wall_seconds = 0;
  bool cpu_measured = true;  // false: the peer gives its loop's wall time only (cpu_seconds is it)
  std::string version;       // the peer's own version string
  nlohmann::ordered_json extra = nlohmann::ordered_json::object();  // e.g. YADE's stiffness
};

struct Adapter {
  const char* name;      // "yade": --peer, --solver, the output folder DIR/yade/
  const char* program;   // default executable, looked up on PATH
  const char* package;   // the Debian package that installs it
  const char* cpu_note;  // what cpu_seconds measures for this peer
  // Throws InputError naming the scene file, the key and why the peer cannot express it.
  void (*check)(const scene::SceneDef& scene);
  // Writes the peer's input into `dir`, runs `exe` there, reads its output back. Throws
  // PeerFailure with the peer's own words when it fails. RunMode::cost runs the peer once, a
  // single process, so its whole run is the children's CPU time around this call.
  PeerTrace (*run)(const scene::SceneDef& scene, const Resolved& resolved,
                   const std::filesystem::path& exe, const std::filesystem::path& dir,
                   RunMode mode);
  // The peer steps at a step of its own (CalculiX's implicit increments) and reads from Resolved
  // only the end, dt × steps: `validate --solver` then gives it the scene's duration instead of
  // running the scene in asperity to resolve a step it would not use (61 s of CPU for the
  // deformable sphere case, twice ccx's 32 s).
  bool own_step = false;
};

// The table of peers; find_adapter throws InputError naming the known ones.
const std::vector<Adapter>& adapters();
const Adapter& find_adapter(const std::string& name);
// The peers' names in the table's order, joined by `separator` ("yade|lammps|...": the help of
// --peer and --solver; ", ": find_adapter's message).
std::string adapter_names(const std::string& separator);

// The executable `name` resolves to on PATH (or itself when it names a path); empty if none.
std::filesystem::path find_executable(const std::string& name);

// The peer's executable: `override_exe` when given, else its default program. Throws InputError
// (usage: exit 2) when it is not installed, naming the Debian package.
std::filesystem::path peer_executable(const Adapter& a, const std::string& override_exe);

// The bodies a trace carries, in scene order: the free spheres, or, when the peer measures the
// contact itself (`PeerTrace::overlap`), every free body (rigid polyhedra).
std::vector<int> traced_bodies(const scene::SceneDef& scene, bool peer_measures_contact);

// The peer's summary.json and force.csv, measured by run/impact_measures.hpp and run/rebound.hpp
// exactly as asperity's runs are. `every`: the scene's record.every (force.csv rows).
run::RunResult measure_trace(const scene::SceneDef& scene, const Resolved& resolved,
                             const PeerTrace& trace, const std::string& peer);

// Runs `a` on the scene into `dir` (DIR/PEER/): cleans what an earlier run left, runs, measures,
// writes summary.json and force.csv (no energy.csv: peers' energy terms are not recorded).
run::RunResult run_peer(const Adapter& a, const std::filesystem::path& exe,
                        const scene::SceneDef& scene, const Resolved& resolved,
                        const std::filesystem::path& dir);

// Shared helpers of the adapters.
std::string shell_quote(const std::string& s);
// Runs a shell command line; its exit code (128 + signal when killed).
int run_command(const std::string& command);
// Writes `text` to `file` through a temporary and a rename.
void write_file(const std::filesystem::path& file, const std::string& text);
// The last non-empty lines of a log, joined with " | " ("(no output)" when none).
std::string log_tail(const std::filesystem::path& file, int lines = 3);
// Runs a peer's translator script (scene_to_yade.py, scene_to_calculix.py): `launch`, the program
// and the script, with DIR/input.json and DIR after it, its output into DIR/PEER.log. Throws
// PeerFailure unless it exits 0 and writes DIR/raw.json, in the peer's own words: error.txt's
// first line (the script writes it), else the log's last lines.
void run_translator(const std::string& peer, const std::string& launch,
                    const std::filesystem::path& dir);

}  // namespace asperity::peers
