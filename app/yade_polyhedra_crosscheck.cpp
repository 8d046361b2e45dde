// The YADE Polyhedra cross-check of rigid mesh bodies under volume-linear (issue 13), as it ran
// before the peer adapters: `asperity crosscheck` hands a scene with mesh bodies here. It is to
// fold into the YADE adapter (validation/peers/yade.cpp); until then it keeps its own driver.
//
// asperity runs as `run` does (DIR/asperity/). The scene, as asperity resolved it (dt, step count,
// the damping of each material pair), goes to DIR/yade/input.json;
// validation/peers/scene_to_yade.py builds it in YADE (`yade -n -x`), times a plain run and records
// YADE's force on the recorded body every step. Both force histories are measured by the same code
// (run/impact_measures.hpp, run/rebound.hpp), so a difference is the codes', not the measuring's.
// docs/crosscheck.md has the law mapping and every systematic difference.
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "app/cli_numbers.hpp"
#include "app/out_folder.hpp"
#include "app/yade_polyhedra_crosscheck.hpp"
#include "contact/restitution_damping.hpp"
#include "core/error.hpp"
#include "io/json_file.hpp"
#include "peers/yade_polyhedra_input.hpp"
#include "run/impact_measures.hpp"
#include "run/rebound.hpp"
#include "run/run_scene.hpp"
#include "scene/scene.hpp"
#include "scene/scene_json.hpp"

#ifndef ASPERITY_YADE_SCRIPT
#error \
    "ASPERITY_YADE_SCRIPT (path of validation/peers/scene_to_yade.py) must be defined by the build"
#endif

namespace asperity::app {
namespace {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// A scene file, or a validation case file (its "scene" object).
scene::SceneDef load_scene_or_case(const fs::path& file) {
  const io::Json json = io::read_json_file(file);
  if (json.is_object() && json.contains("case") && json.contains("scene")) {
    return scene::parse_scene(json.at("scene"), file, "scene");
  }
  return scene::load_scene(file);
}

Json vec(const Vec3& v) {
  return Json::array({v.x(), v.y(), v.z()});
}

const char* law_key(scene::ContactLaw law) {
  switch (law) {
    case scene::ContactLaw::hertz:
      return "hertz";
    case scene::ContactLaw::hertz_mindlin:
      return "hertz-mindlin";
    case scene::ContactLaw::linear:
      return "linear";
    case scene::ContactLaw::potential:
      return "potential";
    case scene::ContactLaw::volume_hertz:
      return "volume-hertz";
    case scene::ContactLaw::volume_linear:
      return "volume-linear";
  }
  return "?";
}

// What scene_to_yade.py reads: the scene with everything asperity derives from it resolved.
Json yade_input(const scene::SceneDef& s, double dt, long steps) {
  const std::string where = s.file.string() + ": ";
  if (s.contact.law == scene::ContactLaw::volume_linear) {
    return peers::yade_polyhedra_input(s, dt, steps);
  }
  if (s.contact.law == scene::ContactLaw::volume_hertz) {
    throw InputError(where +
                     "contact.law: \"volume-hertz\" has no YADE counterpart; cross-check rigid "
                     "polyhedra with \"volume-linear\" (YADE's volumetric law) and a kv");
  }
  Json j;
  j["scene"] = s.name;
  j["law"] = law_key(s.contact.law);
  if (s.contact.law == scene::ContactLaw::potential) {
    throw InputError(where +
                     "contact.law: \"potential\" has no YADE counterpart in the cross-check "
                     "(spheres, planes and boxes with hertz, hertz-mindlin or linear)");
  }
  const contact::NormalLaw normal = s.contact.law == scene::ContactLaw::linear
                                        ? contact::NormalLaw::linear
                                        : contact::NormalLaw::hertz;
  if (s.contact.law == scene::ContactLaw::linear) {
    j["kn"] = *s.contact.kn;
    j["kt"] = s.contact.kt.value_or(2.0 / 7.0 *
                                    *s.contact.kn);  // asperity's default (run/run_spheres.cpp)
  }
  // The hertz law has no tangential force: friction 0 caps YADE's shear force at zero.
  if (s.contact.law == scene::ContactLaw::hertz)
    j["friction_override"] = 0.0;
  else if (s.contact.friction)
    j["friction_override"] = *s.contact.friction;
  else
    j["friction_override"] = nullptr;
  j["materials"] = Json::object();
  for (const Material& m : s.materials) {
    j["materials"][m.name] = {{"density", m.density},
                              {"young", m.young},
                              {"poisson", m.poisson},
                              {"friction", m.friction},
                              {"restitution", m.restitution}};
  }
  j["pairs"] = Json::array();
  for (std::size_t a = 0; a < s.materials.size(); ++a) {
    for (std::size_t b = a; b < s.materials.size(); ++b) {
      const double e =
          s.contact.restitution.value_or(pair_restitution(s.materials[a], s.materials[b]));
      j["pairs"].push_back({{"a", s.materials[a].name},
                            {"b", s.materials[b].name},
                            {"zeta", contact::damping_for_restitution(normal, e)}});
    }
  }
  j["bodies"] = Json::array();
  for (std::size_t k = 0; k < s.bodies.size(); ++k) {
    const scene::BodyDef& b = s.bodies[k];
    Json body{{"name", b.name},
              {"material", s.materials[b.material].name},
              {"fixed", b.fixed},
              {"position", vec(b.position)},
              {"velocity", vec(b.fixed ? Vec3::Zero() : b.velocity)},
              {"angular_velocity", vec(b.fixed ? Vec3::Zero() : b.angular_velocity)}};
    if (b.model != scene::Model::rigid) {
      throw InputError(
          where + "bodies[" + std::to_string(k) + "] \"" + b.name +
          "\": model: the cross-check runs rigid bodies only (YADE has no FEM body here)");
    }
    if (const auto* sp = std::get_if<scene::SphereShape>(&b.shape)) {
      body["shape"] = {{"type", "sphere"}, {"radius", sp->radius}};
    } else if (const auto* pl = std::get_if<scene::PlaneShape>(&b.shape)) {
      body["shape"] = {{"type", "plane"}, {"point", vec(pl->point)}, {"normal", vec(pl->normal)}};
    } else if (const auto* bx = std::get_if<scene::BoxShape>(&b.shape)) {
      body["shape"] = {{"type", "box"}, {"min", vec(bx->min)}, {"max", vec(bx->max)}};
    } else {
      throw InputError(where + "bodies[" + std::to_string(k) + "] \"" + b.name +
                       "\": shape: the cross-check covers spheres, planes and boxes");
    }
    j["bodies"].push_back(body);
  }
  j["gravity"] = vec(s.gravity);
  j["dt"] = dt;
  j["steps"] = steps;
  j["record_body"] = s.bodies[s.record.body].name;
  return j;
}

void write_file(const fs::path& file, const std::string& text) {
  const fs::path tmp = file.string() + ".partial-" + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    if (!out.flush()) throw std::runtime_error(tmp.string() + ": write failed");
  }
  fs::rename(tmp, file);
}

std::string shell_quote(const std::string& s) {
  std::string o = "'";
  for (char c : s) o += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return o + "'";
}

// The executable `name` resolves to on PATH (or itself when it names a path); empty if none.
fs::path find_executable(const std::string& name) {
  if (name.find('/') != std::string::npos)
    return ::access(name.c_str(), X_OK) == 0 ? fs::path(name) : fs::path();
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const fs::path p = fs::path(dir.empty() ? "." : dir) / name;
    if (::access(p.c_str(), X_OK) == 0) return p;
  }
  return {};
}

// YADE's own words for a failure: error.txt's first line, else the log's last non-empty lines.
std::string yade_error_text(const fs::path& dir) {
  std::ifstream err(dir / "error.txt");
  std::string line;
  if (err && std::getline(err, line) && !line.empty()) return line;
  std::ifstream log(dir / "yade.log");
  std::vector<std::string> lines;
  while (std::getline(log, line)) {
    if (line.find_first_not_of(" \t\r") != std::string::npos) lines.push_back(line);
  }
  std::string out;
  for (std::size_t i = lines.size() > 3 ? lines.size() - 3 : 0; i < lines.size(); ++i) {
    out += (out.empty() ? "" : " | ") + lines[i];
  }
  return out.empty() ? "(no output)" : out;
}

struct YadeRow {
  double t, fx, fy, fz, s, rate;
};

std::vector<YadeRow> read_raw_csv(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);  // header
  std::vector<YadeRow> rows;
  while (std::getline(in, line)) {
    YadeRow r{};
    if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf", &r.t, &r.fx, &r.fy, &r.fz, &r.s,
                    &r.rate) != 6) {
      throw std::runtime_error(file.string() + ": unreadable row \"" + line + "\"");
    }
    rows.push_back(r);
  }
  return rows;
}

// YADE's summary.json and force.csv, measured by the code that measures asperity's runs.
run::RunResult yade_result(const scene::SceneDef& s, const Json& raw,
                           const std::vector<YadeRow>& rows) {
  run::RunResult r;
  if (rows.empty()) throw std::runtime_error("YADE recorded no rows");
  run::ImpactMeasures im;
  auto force = [](const YadeRow& row) { return Vec3(row.fx, row.fy, row.fz); };
  im.start(rows[0].t, force(rows[0]), rows[0].s);
  // Restitution as asperity books it (dem/sphere_world.cpp, note_record): the approach speed when
  // the first contact starts, the separation speed when it ends.
  bool touching = rows[0].s > 0;
  int started = touching ? 1 : 0, ended = 0;
  double approach = touching ? rows[0].rate : 0, separation = 0;
  const long every = s.record.every;
  const long n = static_cast<long>(rows.size()) - 1;
  for (long k = 0; k <= n; ++k) {
    const YadeRow& row = rows[k];
    if (k > 0) {
      im.add(row.t, force(row), row.s);
      const bool now = row.s > 0;
      if (!touching && now && started++ == 0) approach = row.rate;
      if (touching && !now && ended++ == 0) separation = -row.rate;
      touching = now;
    }
    if (k % every == 0 || k == n) {
      const Vec3 f = force(row);
      r.force.push_back({row.t, f.x(), f.y(), f.z(), f.norm()});
    }
  }
  r.status = im.first_contact_time < 0 ? "no_contact" : "ok";
  Json& j = r.summary;
  j["status"] = r.status;
  j["scene"] = s.name;
  j["model"] = "yade";
  j["yade_version"] = raw.value("yade_version", "");
  j["contact_law"] = law_key(s.contact.law);
  j["recorded_body"] = s.bodies[s.record.body].name;
  j["peak_force"] = im.peak_force;
  j["impulse"] = im.impulse;
  j["contact_duration"] = im.duration_until(rows.back().t);
  j["first_contact_time"] = im.first_contact_time < 0 ? Json() : Json(im.first_contact_time);
  j["max_overlap"] = im.max_overlap;
  j["restitution"] = ended > 0 && approach > 0 ? Json(separation / approach) : Json();
  if (const auto impact = run::first_impact(s)) {
    auto motion = [&](int body) {
      const Json& f = raw.at("final").at(s.bodies[body].name);
      const auto& v = f.at("velocity");
      const auto& w = f.at("angular_velocity");
      return run::BodyMotion{.v = Vec3(v[0].get<double>(), v[1].get<double>(), v[2].get<double>()),
                             .w = Vec3(w[0].get<double>(), w[1].get<double>(), w[2].get<double>())};
    };
    run::add_rebound_measures(s, *impact, motion(s.record.body), motion(impact->partner), ended > 0,
                              j);
  }
  if (const Json& f = raw.at("final").at(s.bodies[s.record.body].name);
      std::holds_alternative<scene::MeshShape>(s.bodies[s.record.body].shape)) {
    // A rigid polyhedron's rebound: its final speed and spin (run_fdem reports the same keys).
    auto v3 = [](const Json& v) {
      return Vec3(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
    };
    j["final_velocity"] = f.at("velocity");
    j["final_angular_velocity"] = f.at("angular_velocity");
    j["final_speed"] = v3(f.at("velocity")).norm();
    j["final_spin"] = v3(f.at("angular_velocity")).norm();
  }
  j["dt"] = raw.at("dt");
  j["steps"] = raw.at("steps");
  j["simulated_time"] = raw.at("dt").get<double>() * raw.at("steps").get<double>();
  j["cpu_seconds"] = raw.at("cpu_seconds");
  j["wall_seconds"] = raw.at("wall_seconds");
  j["cpu_seconds_note"] =
      "YADE's engine loop alone (a second run, without the per-step Python recorder)";
  j["stiffness"] = raw.at("stiffness");
  return r;
}

Json compare(const Json& a, const Json& y, const std::string& key) {
  Json c;
  c["asperity"] = a.contains(key) ? a.at(key) : Json();
  c["yade"] = y.contains(key) ? y.at(key) : Json();
  if (c["asperity"].is_number() && c["yade"].is_number()) {
    const double va = c["asperity"].get<double>(), vy = c["yade"].get<double>();
    c["rel_diff"] = vy != 0 ? (va - vy) / std::abs(vy) : (va == 0 ? 0.0 : va - vy);
  } else {
    c["rel_diff"] = nullptr;
  }
  return c;
}

}  // namespace

int yade_polyhedra_crosscheck(const fs::path& scene_file, const fs::path& out,
                              const std::string& yade, const fs::path& script,
                              std::optional<double> max_rel_diff, bool quiet) {
  const scene::SceneDef s = load_scene_or_case(scene_file);
  check_out_folder(out);
  const fs::path exe = find_executable(yade);
  if (exe.empty()) {
    throw InputError("crosscheck: YADE not found (\"" + yade +
                     "\" is not an executable on PATH; "
                     "install the Debian package yade or pass --yade PATH)");
  }
  if (!fs::is_regular_file(script))
    throw InputError("crosscheck: " + script.string() + ": YADE translator script not found");

  // A scene YADE cannot carry (a law without a counterpart, a non-convex polyhedron) is refused
  // before anything runs or is written.
  (void)yade_input(s, 0.0, 0);

  // Nothing from an earlier cross-check may be mistaken for this one's.
  fs::create_directories(out / "yade");
  for (const char* f : {"comparison.json"}) fs::remove(out / f);
  for (const char* f :
       {"summary.json", "force.csv", "raw.csv", "raw.json", "error.txt", "yade.log"}) {
    fs::remove(out / "yade" / f);
  }

  const run::RunResult a = run::run_scene(s, {.keep_rows = true});
  run::write_outputs(a, out / "asperity");
  if (a.status == "unstable") {
    std::cerr << "asperity: crosscheck: asperity's run went unstable (" << a.message
              << "); YADE not run\n";
    return kExitUnstable;
  }
  const double dt = a.summary.at("dt").get<double>();
  const long steps = a.summary.at("steps").get<long>();
  const Json input = yade_input(s, dt, steps);
  write_file(out / "yade" / "input.json", input.dump(2) + "\n");

  const std::string cmd = shell_quote(exe.string()) + " -n -x " + shell_quote(script.string()) +
                          " " + shell_quote((out / "yade" / "input.json").string()) + " " +
                          shell_quote((out / "yade").string()) + " > " +
                          shell_quote((out / "yade" / "yade.log").string()) + " 2>&1 < /dev/null";
  const int status = std::system(cmd.c_str());
  const int code =
      status == -1 ? -1 : (WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status));
  if (code != 0 || !fs::exists(out / "yade" / "raw.json")) {
    throw InputError("crosscheck: YADE failed (exit " + std::to_string(code) +
                     "): " + yade_error_text(out / "yade") +
                     " [log: " + (out / "yade" / "yade.log").string() + "]");
  }
  const Json raw = Json::parse(std::ifstream(out / "yade" / "raw.json"));
  const run::RunResult y = yade_result(s, raw, read_raw_csv(out / "yade" / "raw.csv"));
  run::write_outputs(y, out / "yade");
  fs::remove(out / "yade" /
             "energy.csv");  // YADE's energy terms are not recorded (docs/crosscheck.md)

  Json c;
  c["scene"] = s.name;
  c["file"] = scene_file.string();
  c["contact_law"] = law_key(s.contact.law);
  c["dt"] = dt;
  c["steps"] = steps;
  c["status"] = {{"asperity", a.status}, {"yade", y.status}};
  for (const char* q : {"peak_force", "impulse", "contact_duration"})
    c[q] = compare(a.summary, y.summary, q);
  Json more = Json::object();
  for (const char* q :
       {"max_overlap", "first_contact_time", "restitution", "tangential_restitution", "slip_ratio",
        "spin_out", "rebound_angle_deg", "slip_velocity_out", "normal_velocity_out",
        "angular_velocity_change", "tangential_speed_out", "final_speed", "final_spin"}) {
    if (a.summary.contains(q) || y.summary.contains(q)) more[q] = compare(a.summary, y.summary, q);
  }
  c["other"] = more;
  const double cpu_a = a.summary.at("cpu_seconds").get<double>(),
               cpu_y = raw.at("cpu_seconds").get<double>();
  c["cpu_seconds"] = {{"asperity", cpu_a},
                      {"yade", cpu_y},
                      {"ratio_asperity_over_yade", cpu_y > 0 ? Json(cpu_a / cpu_y) : Json()}};
  // The polyhedra path times each of YADE's steps: free flight, in contact, the first and last
  // contact steps (where YADE's intersection is known to be slowest).
  if (raw.contains("step_seconds")) c["yade_step_seconds"] = raw.at("step_seconds");
  {
    const auto& prof = a.summary.contains("profile") ? a.summary.at("profile") : Json();
    if (prof.is_object() && a.summary.contains("steps")) {
      c["asperity_step_seconds"] = {
          {"mean", cpu_a / std::max(1.0, a.summary.at("steps").get<double>())},
          {"contact_phase_total", prof.value("contact", 0.0)},
          {"broad_phase_total", prof.value("broad_phase", 0.0)}};
    }
  }
  double stiff = 0;
  for (const auto& k : raw.at("stiffness")) stiff = std::max(stiff, k.at("rel_diff").get<double>());
  c["stiffness_rel_diff_max"] = stiff;
  c["yade_version"] = raw.value("yade_version", "");
  bool passed = a.status == y.status;
  if (max_rel_diff) {
    for (const char* q : {"peak_force", "impulse", "contact_duration"}) {
      const Json& d = c[q]["rel_diff"];
      passed = passed && d.is_number() && std::abs(d.get<double>()) <= *max_rel_diff;
    }
    c["max_rel_diff"] = *max_rel_diff;
    c["passed"] = passed;
  }
  write_file(out / "comparison.json", c.dump(2) + "\n");
  if (!quiet) {
    std::cerr << s.name << ": peak force " << c["peak_force"]["rel_diff"].dump() << ", impulse "
              << c["impulse"]["rel_diff"].dump() << ", duration "
              << c["contact_duration"]["rel_diff"].dump() << " (asperity - YADE)/YADE; CPU "
              << cpu_a << " s vs " << cpu_y << " s -> " << out.string() << "\n";
  }
  return passed || !max_rel_diff ? kExitOk : kExitFailure;
}

}  // namespace asperity::app
