// The table of peer adapters and what they share: finding the peer, running it, and measuring its
// trace with the code that measures asperity's own runs.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "peers/peer.hpp"
#include "peers/peer_adapters.hpp"
#include "solver/core/error.hpp"
#include "solver/io/atomic_file.hpp"
#include "solver/run/impact_measures.hpp"
#include "solver/run/rebound.hpp"
#include "solver/run/summary.hpp"

namespace asperity::peers {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

const std::vector<Adapter>& adapters() {
  static const std::vector<Adapter> table{yade_adapter(), lammps_adapter(), liggghts_adapter(),
                                          calculix_adapter()};
  return table;
}

const Adapter& find_adapter(const std::string& name) {
  for (const Adapter& a : adapters()) {
    if (name == a.name) return a;
  }
  throw InputError("--peer " + name + ": unknown peer (known: " + adapter_names(", ") + ")");
}

std::string adapter_names(const std::string& separator) {
  std::string names;
  for (const Adapter& a : adapters()) names += (names.empty() ? "" : separator) + a.name;
  return names;
}

fs::path find_executable(const std::string& name) {
  if (name.empty()) return {};
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

fs::path peer_executable(const Adapter& a, const std::string& override_exe) {
  const std::string name = override_exe.empty() ? a.program : override_exe;
  const fs::path exe = find_executable(name);
  if (exe.empty()) {
    throw InputError(std::string(a.name) + ": not installed (\"" + name +
                     "\" is not an executable on PATH; install the Debian package " + a.package +
                     ")");
  }
  return exe;
}

std::string shell_quote(const std::string& s) {
  std::string o = "'";
  for (char c : s) o += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return o + "'";
}

int run_command(const std::string& command) {
  const int status = std::system(command.c_str());
  if (status == -1) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

void write_file(const fs::path& file, const std::string& text) {
  io::write_atomically(file, text);
}

std::string log_tail(const fs::path& file, int n) {
  std::ifstream log(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(log, line);) {
    if (line.find_first_not_of(" \t\r") != std::string::npos) lines.push_back(line);
  }
  std::string out;
  const std::size_t from = lines.size() > static_cast<std::size_t>(n) ? lines.size() - n : 0;
  for (std::size_t i = from; i < lines.size(); ++i) out += (out.empty() ? "" : " | ") + lines[i];
  return out.empty() ? "(no output)" : out;
}

void run_translator(const std::string& peer, const std::string& launch, const fs::path& dir) {
  const fs::path log = dir / (peer + ".log");
  const int code = run_command(launch + " " + shell_quote((dir / "input.json").string()) + " " +
                               shell_quote(dir.string()) + " > " + shell_quote(log.string()) +
                               " 2>&1 < /dev/null");
  if (code != 0 || !fs::exists(dir / "raw.json")) {
    std::ifstream err(dir / "error.txt");
    std::string why;
    if (!err || !std::getline(err, why) || why.empty()) why = log_tail(log);
    throw PeerFailure(peer + " failed (exit " + std::to_string(code) + "): " + why +
                      " [log: " + log.string() + "]");
  }
}

std::vector<int> free_spheres(const scene::SceneDef& s) {
  std::vector<int> out;
  for (std::size_t k = 0; k < s.bodies.size(); ++k) {
    if (!s.bodies[k].fixed && std::holds_alternative<scene::SphereShape>(s.bodies[k].shape))
      out.push_back(static_cast<int>(k));
  }
  return out;
}

std::vector<int> traced_bodies(const scene::SceneDef& s, bool peer_measures_contact) {
  if (!peer_measures_contact) return free_spheres(s);
  std::vector<int> out;
  for (std::size_t k = 0; k < s.bodies.size(); ++k) {
    if (!s.bodies[k].fixed) out.push_back(static_cast<int>(k));
  }
  return out;
}

PeerTrace read_trace_csv(const fs::path& file, int bodies, const std::string& peer,
                         bool own_contact) {
  std::ifstream in(file);
  if (!in) throw PeerFailure(peer + ": " + file.string() + " was not written");
  std::string line;
  std::getline(in, line);  // header
  PeerTrace tr;
  const std::size_t first_body = own_contact ? 8 : 4;
  const std::size_t columns = first_body + 6 * static_cast<std::size_t>(bodies);
  std::vector<double> row(columns);
  while (std::getline(in, line)) {
    std::size_t k = 0;
    const char* p = line.c_str();
    char* end = nullptr;
    for (; k < columns; ++k) {
      row[k] = std::strtod(p, &end);
      if (end == p) break;
      p = *end == ',' ? end + 1 : end;
    }
    if (k != columns)
      throw PeerFailure(peer + ": " + file.string() + ": unreadable row \"" + line + "\"");
    tr.t.push_back(row[0]);
    tr.force.emplace_back(row[1], row[2], row[3]);
    if (own_contact) {
      tr.overlap.push_back(row[4]);
      tr.normal.emplace_back(row[5], row[6], row[7]);
    }
    tr.x.emplace_back();
    tr.v.emplace_back();
    for (int b = 0; b < bodies; ++b) {
      const double* c = &row[first_body + 6 * static_cast<std::size_t>(b)];
      tr.x.back().emplace_back(c[0], c[1], c[2]);
      tr.v.back().emplace_back(c[3], c[4], c[5]);
    }
  }
  return tr;
}

namespace {

// Signed overlap (m) of a sphere at x with radius r against body b, the unit normal from b into
// the sphere, and b's velocity (zero unless a free sphere): the geometry of dem/sphere_world.cpp.
struct Gap {
  double s = -1e300;
  Vec3 n = Vec3::UnitZ();
};
Gap gap(const Vec3& x, double r, const scene::BodyDef& b, const Vec3& xb) {
  Gap g;
  if (const auto* sp = std::get_if<scene::SphereShape>(&b.shape)) {
    const Vec3 d = x - xb;
    const double dist = d.norm();
    g.s = r + sp->radius - dist;
    if (dist > 0) g.n = d / dist;
  } else if (const auto* pl = std::get_if<scene::PlaneShape>(&b.shape)) {
    g.n = pl->normal.normalized();
    g.s = r - (x - pl->point).dot(g.n);
  } else if (const auto* bx = std::get_if<scene::BoxShape>(&b.shape)) {
    const Vec3 c = x.cwiseMax(bx->min).cwiseMin(bx->max);
    const double dist = (x - c).norm();
    g.s = dist > 0 ? r - dist : r;
    if (dist > 0) g.n = (x - c) / dist;
  }
  return g;
}

}  // namespace

run::RunResult measure_trace(const scene::SceneDef& s, const Resolved& resolved,
                             const PeerTrace& tr, const std::string& peer) {
  const std::size_t n = tr.t.size();
  if (n == 0) throw PeerFailure(peer + ": recorded no steps");
  const bool own_contact = !tr.overlap.empty();
  if (own_contact && (tr.overlap.size() != n || tr.normal.size() != n))
    throw PeerFailure(peer + ": the trace's overlaps and normals are not one per sample");
  // The traced bodies in scene order: the trace's columns.
  std::vector<int> free_index(s.bodies.size(), -1);
  std::vector<bool> free(s.bodies.size(), false);
  int nfree = 0;
  for (int k : traced_bodies(s, own_contact)) {
    free_index[static_cast<std::size_t>(k)] = nfree++;
    free[static_cast<std::size_t>(k)] = true;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (tr.x[i].size() != static_cast<std::size_t>(nfree) || tr.v[i].size() != tr.x[i].size())
      throw PeerFailure(peer + ": trace sample " + std::to_string(i) + " has " +
                        std::to_string(tr.x[i].size()) + " bodies, the scene " +
                        std::to_string(nfree) + " traced bodies");
  }
  const int rec = s.record.body;
  auto pos = [&](std::size_t i, int body) {
    const int f = free_index[static_cast<std::size_t>(body)];
    return f < 0 ? s.bodies[static_cast<std::size_t>(body)].position
                 : tr.x[i][static_cast<std::size_t>(f)];
  };
  auto vel = [&](std::size_t i, int body) {
    const int f = free_index[static_cast<std::size_t>(body)];
    return f < 0 ? Vec3(Vec3::Zero()) : tr.v[i][static_cast<std::size_t>(f)];
  };
  // The recorded body's largest signed overlap over every contact it can have and that
  // contact's normal, pointing into the recorded body: what the worlds' contact output
  // (core/body_contacts.hpp) feeds asperity's own measures.
  struct Sample {
    double s = -1e300;
    Vec3 n = Vec3::UnitZ();
  };
  auto contact_state = [&](std::size_t i) {
    if (own_contact) return Sample{tr.overlap[i], tr.normal[i]};
    Sample best;
    auto consider = [&](int sphere, int other, double sign) {
      const double radius =
          std::get<scene::SphereShape>(s.bodies[static_cast<std::size_t>(sphere)].shape).radius;
      const Gap g =
          gap(pos(i, sphere), radius, s.bodies[static_cast<std::size_t>(other)], pos(i, other));
      if (g.s > best.s) best = {g.s, sign * g.n};
    };
    const bool rec_is_sphere =
        std::holds_alternative<scene::SphereShape>(s.bodies[static_cast<std::size_t>(rec)].shape);
    for (int b = 0; b < static_cast<int>(s.bodies.size()); ++b) {
      if (b == rec) continue;
      if (rec_is_sphere)
        consider(rec, b, 1.0);
      else if (std::holds_alternative<scene::SphereShape>(
                   s.bodies[static_cast<std::size_t>(b)].shape))
        consider(b, rec, -1.0);  // a plane or box meets spheres only
    }
    return best;
  };
  // Restitution: one definition for every model and peer (run/impact_measures.hpp), the normal
  // force being the recorded force's component along the deepest contact's normal.
  const int partner = run::restitution_partner(rec, free);
  auto relative_velocity = [&](std::size_t i) {
    return Vec3(vel(i, rec) - (partner >= 0 ? vel(i, partner) : Vec3(Vec3::Zero())));
  };

  run::RunResult r;
  run::ImpactMeasures im;
  run::Restitution restitution;
  im.start(tr.t[0], tr.force[0], contact_state(0).s);
  const long every = std::max(1, s.record.every);
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0) {
      const Sample c = contact_state(i);
      const bool before = im.touching;
      im.add(tr.t[i], tr.force[i], c.s);
      const Vec3 normal_force = tr.force[i].dot(c.n) * c.n;
      restitution.add(before, im.touching, relative_velocity(i - 1), relative_velocity(i),
                      normal_force, tr.t[i] - tr.t[i - 1]);
    }
    if (static_cast<long>(i) % every == 0 || i + 1 == n) {
      const Vec3& f = tr.force[i];
      r.force.push_back({tr.t[i], f.x(), f.y(), f.z(), f.norm()});
    }
  }
  r.status = im.first_contact_time < 0 ? "no_contact" : "ok";
  run::SummaryJson& j = r.summary;
  const run::RunIdentity id{.scene = s.name,
                            .model = peer,
                            .contact_law = scene::contact_law_name(s.contact.law),
                            .recorded_body = s.bodies[static_cast<std::size_t>(rec)].name};
  run::write_measures(j, id, r.status, "", im, tr.t.back(), restitution.value(), std::nullopt);
  j["peer_version"] = tr.version;
  // The peak both codes compare on a deformable body: the T/20 moving average, and how much of
  // the raw peak lies above it (what asperity's mesh runs report, run_fdem.cpp).
  j["peak_force_filtered"] = im.filtered_peak();
  j["ringing_amplitude"] = im.ringing_amplitude();
  if (const auto impact = run::first_impact(s)) {
    auto motion = [&](int body) {
      const int f = free_index[static_cast<std::size_t>(body)];
      if (f < 0) return run::BodyMotion{};
      return run::BodyMotion{.v = tr.v[n - 1][static_cast<std::size_t>(f)],
                             .w = tr.final_w.at(static_cast<std::size_t>(f))};
    };
    run::add_rebound_measures(s, *impact, motion(rec), motion(impact->partner), restitution.ended(),
                              j);
  }
  if (const int f = free_index[static_cast<std::size_t>(rec)]; f >= 0) {
    // The recorded body's final state, the keys asperity's runners report (run_spheres.cpp; a
    // rigid polyhedron's spin as run_fdem.cpp reports it).
    const Vec3 v = tr.v[n - 1][static_cast<std::size_t>(f)];
    const Vec3 w = tr.final_w.at(static_cast<std::size_t>(f));
    j["final_velocity"] = {v.x(), v.y(), v.z()};
    j["final_speed"] = v.norm();
    j["final_angular_velocity"] = {w.x(), w.y(), w.z()};
    if (std::holds_alternative<scene::MeshShape>(s.bodies[static_cast<std::size_t>(rec)].shape))
      j["final_spin"] = w.norm();
  }
  j["dt"] = resolved.dt;
  run::write_run(j, resolved.steps, resolved.dt * static_cast<double>(resolved.steps), false,
                 tr.cpu_seconds, tr.wall_seconds);
  for (const Adapter& a : adapters())
    if (peer == a.name) j["cpu_seconds_note"] = a.cpu_note;
  for (const auto& [k, v] : tr.extra.items()) j[k] = v;
  return r;
}

run::RunResult run_peer(const Adapter& a, const fs::path& exe, const scene::SceneDef& scene,
                        const Resolved& resolved, const fs::path& dir) {
  // Nothing from an earlier run may be mistaken for this one's.
  io::empty_output_folder(dir);
  const PeerTrace tr = a.run(scene, resolved, exe, dir, RunMode::trace);
  run::RunResult r = measure_trace(scene, resolved, tr, a.name);
  run::write_outputs(r, dir);
  io::remove_earlier_output(
      dir / "energy.csv");  // peers' energy terms are not recorded (docs/crosscheck.md)
  return r;
}

}  // namespace asperity::peers
