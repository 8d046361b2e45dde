// The cross-check: asperity runs as `run` does (DIR/asperity/); every peer runs the scene as
// asperity resolved it (same dt and step count) into DIR/PEER/; all force histories are measured
// by the same code (peers.cpp, run/impact_measures.hpp), so a difference is the codes', not the
// measuring's. docs/crosscheck.md has each peer's mapping and every systematic difference.
#include "crosscheck.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>

#include "core/error.hpp"
#include "io/json_file.hpp"
#include "junit.hpp"
#include "peer.hpp"
#include "run/run_scene.hpp"
#include "scene/scene_json.hpp"

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
constexpr const char* kOther[] = {"max_overlap",
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

}  // namespace

int crosscheck(const CrosscheckOptions& o) {
  const scene::SceneDef s = load_scene_or_case(o.scene_file);
  // Every peer is found and asked first: bad input is reported before anything runs or is written.
  if (o.peers.empty()) throw InputError("crosscheck: --peer: name at least one peer");
  std::vector<Planned> plan;
  std::vector<std::pair<std::string, std::string>> not_run;  // peer, why it cannot express s
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

  fs::create_directories(o.out);
  fs::remove(o.out / "comparison.json");
  if (o.junit) fs::remove(*o.junit);
  const run::RunResult a = run::run_scene(s, {.keep_rows = true});
  run::write_outputs(a, o.out / "asperity");
  if (a.status == "unstable") {
    std::cerr << "asperity: crosscheck: asperity's run went unstable (" << a.message
              << "); no peer run\n";
    return kExitUnstable;
  }
  const Resolved resolved{.dt = a.summary.at("dt").get<double>(),
                          .steps = a.summary.at("steps").get<long>()};

  std::vector<std::pair<std::string, Json>> done;  // peer -> summary
  std::vector<std::pair<std::string, std::string>> failed;
  for (const Planned& p : plan) {
    try {
      done.emplace_back(p.adapter->name,
                        run_peer(*p.adapter, p.exe, s, resolved, o.out / p.adapter->name).summary);
    } catch (const PeerFailure& e) {
      failed.emplace_back(p.adapter->name, e.what());
    }
  }

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

  // The gate: per peer, the three contract quantities within max_rel_diff and the same status.
  std::vector<validation::JUnitCase> junit;
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
  if (o.max_rel_diff) {
    c["max_rel_diff"] = *o.max_rel_diff;
    c["passed"] = passed;
  }
  write_file(o.out / "comparison.json", c.dump(2) + "\n");
  if (o.junit) validation::write_junit(*o.junit, "asperity crosscheck " + s.name, junit);

  for (const auto& [name, why] : failed) std::cerr << "asperity: crosscheck: " << why << "\n";
  if (!o.quiet) {
    for (const auto& [name, summary] : done) {
      std::cerr << s.name << " vs " << name << ": peak force "
                << c["peak_force"]["rel_diff"][name].dump() << ", impulse "
                << c["impulse"]["rel_diff"][name].dump() << ", duration "
                << c["contact_duration"]["rel_diff"][name].dump() << " (asperity - " << name << ")/"
                << name << "; CPU " << cpu_a << " s vs " << summary.at("cpu_seconds").get<double>()
                << " s\n";
    }
    if (failed.empty()) std::cerr << "-> " << o.out.string() << "\n";
  }
  if (!failed.empty()) return kExitFailure;
  return passed || !o.max_rel_diff ? kExitOk : kExitFailure;
}

}  // namespace asperity::peers
