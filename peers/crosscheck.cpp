// The cross-check: asperity runs as `run` does (DIR/asperity/); every peer runs the scene as
// asperity resolved it (same dt and step count) into DIR/PEER/; all force histories are measured
// by the same code (peers.cpp, run/impact_measures.hpp), so a difference is the codes', not the
// measuring's. docs/crosscheck.md has each peer's mapping and every systematic difference.
#include "peers/crosscheck.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>

#include "peers/peer.hpp"
#include "solver/core/clock.hpp"
#include "solver/core/error.hpp"
#include "solver/io/atomic_file.hpp"
#include "solver/io/json_file.hpp"
#include "solver/io/printable.hpp"
#include "solver/run/run_scene.hpp"
#include "solver/scene/scene_json.hpp"
#include "validation/junit.hpp"

namespace asperity::peers {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

scene::SceneDef load_scene_or_case(const fs::path& file) {
  const io::Json json = io::read_json_file(file);
  if (json.is_object() && json.contains("case") && json.contains("scene")) {
    return scene::parse_scene(json.at("scene"), file, "scene");
  }
  return scene::load_scene(file);
}

namespace {

constexpr const char* kGated[] = {"peak_force", "impulse", "contact_duration"};
constexpr const char* kOther[] = {"peak_force_filtered",
                                  "ringing_amplitude",
                                  "max_overlap",
                                  "first_contact_time",
                                  "restitution",
                                  "tangential_restitution",
                                  "slip_ratio",
                                  "spin_out",
                                  "rebound_angle_deg",
                                  "slip_velocity_out",
                                  "normal_velocity_out",
                                  "angular_velocity_change",
                                  "tangential_speed_out",
                                  "final_speed",
                                  "final_spin"};

Json rel_diff(const Json& a, const Json& p) {
  if (!a.is_number() || !p.is_number()) return nullptr;
  const double va = a.get<double>(), vp = p.get<double>();
  return vp != 0 ? (va - vp) / std::abs(vp) : (va == 0 ? 0.0 : va - vp);
}

// {"asperity": a, PEER: value..., "rel_diff": {PEER: (a − peer)/|peer|}}
Json compare(const Json& a, const std::vector<std::pair<std::string, Json>>& peers,
             const std::string& key) {
  Json c;
  c["asperity"] = a.contains(key) ? a.at(key) : Json();
  Json d = Json::object();
  for (const auto& [name, summary] : peers) {
    c[name] = summary.contains(key) ? summary.at(key) : Json();
    d[name] = rel_diff(c["asperity"], c[name]);
  }
  c["rel_diff"] = d;
  return c;
}

struct Planned {
  const Adapter* adapter;
  fs::path exe;
};

// CPU seconds of the terminated, waited-for children (and theirs): a peer's whole process.
double children_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_CHILDREN, &u);
  auto sec = [](const timeval& t) {
    return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
  };
  return sec(u.ru_utime) + sec(u.ru_stime);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// One code's cost. step_cpu: the CPU the steps cost, from which the per-step, per-particle figure.
Json cost_entry(double step_cpu, double loop_cpu, double loop_wall, double run_cpu, double run_wall,
                long steps, std::size_t particles, const std::string& version,
                const std::string& note) {
  const double per = static_cast<double>(std::max(steps, 1L)) *
                     static_cast<double>(std::max<std::size_t>(particles, 1));
  return {{"step_cpu_seconds", step_cpu}, {"cpu_per_step_per_particle", step_cpu / per},
          {"loop_cpu_seconds", loop_cpu}, {"loop_wall_seconds", loop_wall},
          {"run_cpu_seconds", run_cpu},   {"run_wall_seconds", run_wall},
          {"version", version},           {"loop_note", note}};
}

// A peer's plain run as a process: its CPU (children's) and wall seconds, and what it reported.
struct ProcessRun {
  PeerTrace trace;
  double cpu = 0, wall = 0;
};
ProcessRun timed_run(const Planned& p, const scene::SceneDef& s, const Resolved& r,
                     const fs::path& dir) {
  // Nothing from an earlier run may be mistaken for this one's.
  io::empty_output_folder(dir);
  ProcessRun out;
  const double cpu0 = children_cpu_seconds();
  const auto wall0 = std::chrono::steady_clock::now();
  out.trace = p.adapter->run(s, r, p.exe, dir, RunMode::cost);
  out.wall = seconds_since(wall0);
  out.cpu = children_cpu_seconds() - cpu0;
  return out;
}

// The cost table's run: each peer's plain run alone, timed as a process; DIR/cost.json.
int cost_only(const CrosscheckOptions& o, const scene::SceneDef& s, const run::RunResult& a,
              double run_cpu, double run_wall, const Resolved& resolved,
              const std::vector<Planned>& plan) {
  std::size_t particles = 0;
  for (const scene::BodyDef& b : s.bodies)
    particles += !b.fixed && std::holds_alternative<scene::SphereShape>(b.shape) ? 1 : 0;
  Json c;
  c["scene"] = s.name;
  c["file"] = o.scene_file.string();
  c["particles"] = particles;
  c["dt"] = resolved.dt;
  c["steps"] = resolved.steps;
  // asperity's steps: its time loop's thread CPU (run/time_loop.hpp), set-up excluded.
  const double loop_cpu = a.summary.at("cpu_seconds").get<double>();
  c["codes"]["asperity"] =
      cost_entry(loop_cpu, loop_cpu, a.summary.at("wall_seconds").get<double>(), run_cpu, run_wall,
                 resolved.steps, particles, "asperity 0.1.0",
                 "asperity's time loop (its per-step recording of the recorded body included)");
  c["codes"]["asperity"]["step_cpu_from"] = "asperity's time-loop thread CPU";
  std::vector<std::string> failed;
  for (const Planned& p : plan) {
    // The steps' CPU: the peer's own CPU clock of its loop (YADE: process_time around O.run;
    // LAMMPS: loop time × its CPU use), else (LIGGGHTS prints its loop's wall time only) its
    // process CPU at the scene's step count less the same process at 0 steps (start, input,
    // set-up, exit; into DIR/setup/PEER/), which every peer also gets as a cross-check.
    try {
      const fs::path dir = o.out / p.adapter->name;
      const ProcessRun setup =
          timed_run(p, s, {.dt = resolved.dt, .steps = 0}, o.out / "setup" / p.adapter->name);
      const ProcessRun full = timed_run(p, s, resolved, dir);
      const double by_process = full.cpu - setup.cpu;
      Json e = cost_entry(full.trace.cpu_measured ? full.trace.cpu_seconds : by_process,
                          full.trace.cpu_seconds, full.trace.wall_seconds, full.cpu, full.wall,
                          resolved.steps, particles, full.trace.version, p.adapter->cpu_note);
      e["step_cpu_from"] =
          full.trace.cpu_measured ? "the peer's loop CPU clock" : "process CPU less a 0-step run";
      e["process_step_cpu_seconds"] = by_process;
      e["setup_cpu_seconds"] = setup.cpu;
      c["codes"][p.adapter->name] = e;
    } catch (const PeerFailure& e) {
      c["failed"][p.adapter->name] = e.what();
      failed.push_back(e.what());
    }
  }
  write_file(o.out / "cost.json", c.dump(2) + "\n");
  for (const std::string& why : failed) std::cerr << "asperity: crosscheck: " << why << "\n";
  if (!o.quiet && failed.empty()) std::cerr << "-> " << (o.out / "cost.json").string() << "\n";
  return failed.empty() ? kExitOk : kExitFailure;
}

using Reasons = std::vector<std::pair<std::string, std::string>>;  // peer, why
using Summaries = std::vector<std::pair<std::string, Json>>;       // peer, its summary.json

// Every peer found and asked whether it can express the scene, before anything runs or is
// written: bad input is reported first. A peer that cannot express it is an error, or with
// --only-expressible a reason in `not_run`.
std::vector<Planned> plan_peers(const CrosscheckOptions& o, const scene::SceneDef& s,
                                Reasons& not_run) {
  if (o.peers.empty()) throw InputError("crosscheck: --peer: name at least one peer");
  if (o.cost_only && (o.max_rel_diff || o.junit))
    throw InputError("crosscheck: --cost-only compares nothing: drop --max-rel-diff and --junit");
  std::vector<Planned> plan;
  for (const std::string& name : o.peers) {
    const Adapter& a = find_adapter(name);
    for (const Planned& p : plan)
      if (p.adapter == &a) throw InputError("--peer " + name + ": named twice");
    try {
      a.check(s);
    } catch (const InputError& e) {
      if (!o.only_expressible) throw;
      not_run.emplace_back(name, e.what());
      continue;
    }
    const auto it = o.programs.find(name);
    plan.push_back({&a, peer_executable(a, it == o.programs.end() ? "" : it->second)});
  }
  return plan;
}

// comparison.json: the identity of the run, each code's status, the gated and the other
// quantities side by side with their relative differences, CPU and, where a peer times its kinds
// of step, the cost per step.
Json comparison(const CrosscheckOptions& o, const scene::SceneDef& s, const run::RunResult& a,
                const Resolved& resolved, const std::vector<Planned>& plan, const Reasons& not_run,
                const Summaries& done, const Reasons& failed) {
  Json c;
  c["scene"] = s.name;
  c["file"] = o.scene_file.string();
  c["contact_law"] = a.summary.value("contact_law", "");
  c["recorded_body"] = s.bodies[s.record.body].name;
  c["dt"] = resolved.dt;
  c["steps"] = resolved.steps;
  c["peers"] = Json::array();
  for (const Planned& p : plan) c["peers"].push_back(p.adapter->name);
  if (!not_run.empty()) {
    c["not_run"] = Json::object();
    for (const auto& [name, why] : not_run) c["not_run"][name] = why;
  }
  c["status"] = {{"asperity", a.status}};
  for (const auto& [name, summary] : done) c["status"][name] = summary.at("status");
  for (const auto& [name, why] : failed) c["status"][name] = "failed: " + why;
  for (const char* q : kGated) c[q] = compare(a.summary, done, q);
  Json more = Json::object();
  for (const char* q : kOther) {
    bool any = a.summary.contains(q);
    for (const auto& d : done) any = any || d.second.contains(q);
    if (any) more[q] = compare(a.summary, done, q);
  }
  c["other"] = more;
  const double cpu_a = a.summary.at("cpu_seconds").get<double>();
  c["cpu_seconds"] = {{"asperity", cpu_a}};
  Json ratio = Json::object();
  for (const auto& [name, summary] : done) {
    const double cpu_p = summary.at("cpu_seconds").get<double>();
    c["cpu_seconds"][name] = cpu_p;
    ratio[name] = cpu_p > 0 ? Json(cpu_a / cpu_p) : Json();
  }
  c["cpu_seconds"]["ratio_asperity_over"] = ratio;
  Json versions = Json::object();
  for (const auto& [name, summary] : done) {
    versions[name] = summary.value("peer_version", "");
    if (summary.contains("stiffness_rel_diff_max"))
      c["stiffness_rel_diff_max"][name] = summary.at("stiffness_rel_diff_max");
  }
  c["versions"] = versions;
  // Cost per step, side by side, where a peer times its kinds of step (YADE's polyhedra: wall
  // seconds of free flight, in contact, the first and last contact steps): asperity's mean CPU per
  // step and the wall seconds of its contact and broad phases over the run (its profile).
  Json steps_cost = Json::object();
  for (const auto& [name, summary] : done)
    if (summary.contains("step_seconds")) steps_cost[name] = summary.at("step_seconds");
  if (!steps_cost.empty()) {
    const Json& prof = a.summary.contains("profile") ? a.summary.at("profile") : Json();
    Json mine{{"cpu_mean", cpu_a / std::max(1.0, static_cast<double>(resolved.steps))}};
    if (prof.is_object()) {
      mine["contact_phase_wall"] = prof.value("contact", 0.0);
      mine["broad_phase_wall"] = prof.value("broad_phase", 0.0);
    }
    c["step_seconds"] = {{"asperity", mine}};
    for (const auto& [name, v] : steps_cost.items()) c["step_seconds"][name] = v;
  }
  return c;
}

// The gate: per peer, the three contract quantities within max_rel_diff and the same status.
// Fills `junit` (one case per peer and gated quantity, a skipped or failed run one case each);
// whether every peer passed.
bool gate(const CrosscheckOptions& o, const scene::SceneDef& s, const run::RunResult& a, Json& c,
          const Reasons& not_run, const Summaries& done, const Reasons& failed,
          std::vector<validation::JUnitCase>& junit) {
  bool passed = failed.empty();
  for (const auto& [name, why] : not_run) {
    junit.push_back({.classname = s.name + "." + name,
                     .name = "run",
                     .skipped = true,
                     .message = name + " not run: " + why});
  }
  for (const auto& [name, why] : failed) {
    junit.push_back({.classname = s.name + "." + name,
                     .name = "run",
                     .error = true,
                     .message = name + " failed",
                     .details = why});
  }
  for (const auto& [name, summary] : done) {
    const bool same_status = summary.at("status") == a.summary.at("status");
    passed = passed && same_status;
    junit.push_back({.classname = s.name + "." + name,
                     .name = "status",
                     .failed = !same_status,
                     .message = "status: asperity " + a.status + ", " + name + " " +
                                summary.at("status").get<std::string>()});
    for (const char* q : kGated) {
      const Json& d = c[q]["rel_diff"][name];
      const bool ok =
          !o.max_rel_diff || (d.is_number() && std::abs(d.get<double>()) <= *o.max_rel_diff);
      passed = passed && ok;
      junit.push_back(
          {.classname = s.name + "." + name,
           .name = q,
           .seconds = summary.at("cpu_seconds").get<double>(),
           .failed = !ok,
           .message = std::string(q) + ": asperity " + c[q]["asperity"].dump() + ", " + name + " " +
                      c[q][name].dump() + ", relative difference " + d.dump() +
                      (o.max_rel_diff ? ", tolerance " + Json(*o.max_rel_diff).dump() : ""),
           .details = "(asperity - peer)/|peer|; docs/crosscheck.md gives the reasons for each "
                      "tolerance"});
    }
  }
  return passed;
}

// The failures, and unless quiet each peer's differences and CPU, on stderr.
void report(const CrosscheckOptions& o, const scene::SceneDef& s, const run::RunResult& a, Json& c,
            const Summaries& done, const Reasons& failed) {
  const double cpu_a = a.summary.at("cpu_seconds").get<double>();
  for (const auto& [name, why] : failed) std::cerr << "asperity: crosscheck: " << why << "\n";
  if (!o.quiet) {
    for (const auto& [name, summary] : done) {
      std::cerr << io::printable(s.name, io::kEchoChars) << " vs " << name << ": peak force "
                << c["peak_force"]["rel_diff"][name].dump() << ", impulse "
                << c["impulse"]["rel_diff"][name].dump() << ", duration "
                << c["contact_duration"]["rel_diff"][name].dump() << " (asperity - " << name << ")/"
                << name << "; CPU " << cpu_a << " s vs " << summary.at("cpu_seconds").get<double>()
                << " s\n";
    }
    if (failed.empty()) std::cerr << "-> " << o.out.string() << "\n";
  }
}

}  // namespace

int crosscheck(const CrosscheckOptions& o) {
  const scene::SceneDef s = load_scene_or_case(o.scene_file);
  Reasons not_run;  // peer, why it cannot express s
  const std::vector<Planned> plan = plan_peers(o, s, not_run);

  fs::create_directories(o.out);
  io::remove_earlier_output(o.out / "comparison.json");
  io::remove_earlier_output(o.out / "cost.json");
  if (o.junit) io::remove_earlier_output(*o.junit);
  const double cpu0 = cpu_seconds();
  const auto wall0 = std::chrono::steady_clock::now();
  const run::RunResult a = run::run_scene(s, {.keep_rows = true});
  run::write_outputs(a, o.out / "asperity");
  const double run_cpu = cpu_seconds() - cpu0, run_wall = seconds_since(wall0);
  if (a.status == "unstable") {
    std::cerr << "asperity: crosscheck: asperity's run went unstable (" << a.message
              << "); no peer run\n";
    return kExitUnstable;
  }
  const Resolved resolved{.dt = a.summary.at("dt").get<double>(),
                          .steps = a.summary.at("steps").get<long>()};
  if (o.cost_only) return cost_only(o, s, a, run_cpu, run_wall, resolved, plan);

  Summaries done;
  Reasons failed;
  for (const Planned& p : plan) {
    try {
      done.emplace_back(p.adapter->name,
                        run_peer(*p.adapter, p.exe, s, resolved, o.out / p.adapter->name).summary);
    } catch (const PeerFailure& e) {
      failed.emplace_back(p.adapter->name, e.what());
    }
  }

  Json c = comparison(o, s, a, resolved, plan, not_run, done, failed);
  std::vector<validation::JUnitCase> junit;
  const bool passed = gate(o, s, a, c, not_run, done, failed, junit);
  if (o.max_rel_diff) {
    c["max_rel_diff"] = *o.max_rel_diff;
    c["passed"] = passed;
  }
  write_file(o.out / "comparison.json", c.dump(2) + "\n");
  if (o.junit) validation::write_junit(*o.junit, "asperity crosscheck " + s.name, junit);

  report(o, s, a, c, done, failed);
  if (!failed.empty()) return kExitFailure;
  return passed || !o.max_rel_diff ? kExitOk : kExitFailure;
}

}  // namespace asperity::peers
