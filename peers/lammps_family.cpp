// Shared by the LAMMPS and LIGGGHTS adapters: checks, per-pair constants, dump and log readers.
#include "peers/lammps_family.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include "peers/peer_adapters.hpp"
#include "solver/core/error.hpp"
#include "solver/scene/resolve.hpp"

namespace asperity::peers::lammps_family {
namespace fs = std::filesystem;

void check_common(const scene::SceneDef& s, const char* peer) {
  const std::string where = s.file.string() + ": ";
  for (std::size_t k = 0; k < s.bodies.size(); ++k) {
    const scene::BodyDef& b = s.bodies[k];
    const std::string at = where + "bodies[" + std::to_string(k) + "] \"" + b.name + "\": ";
    if (b.model != scene::Model::rigid)
      throw InputError(at + "model: " + peer + ": the adapter runs rigid spheres only");
    if (std::holds_alternative<scene::MeshShape>(b.shape)) {
      throw InputError(at + "shape: " + peer +
                       ": a mesh body has no counterpart (its granular styles are spheres)");
    }
    if (std::holds_alternative<scene::BoxShape>(b.shape)) {
      throw InputError(at + "shape: " + peer +
                       ": a box is not mapped (the adapter maps axis-aligned planes to "
                       "fix wall/gran; use YADE for boxes)");
    }
    if (const auto* pl = std::get_if<scene::PlaneShape>(&b.shape)) {
      const Vec3 n = pl->normal.normalized();
      int axes = 0;
      for (int a = 0; a < 3; ++a) axes += std::abs(std::abs(n[a]) - 1) < 1e-12 ? 1 : 0;
      if (axes != 1) {
        throw InputError(at + "shape.normal: " + peer +
                         ": fix wall/gran planes are normal to x, y or z; this one is not");
      }
    }
    if (b.fixed && std::holds_alternative<scene::SphereShape>(b.shape)) {
      throw InputError(at + "fixed: " + peer +
                       ": a fixed sphere is not mapped (fix freeze would zero the force that is "
                       "recorded on it)");
    }
  }
  if (const int n = atom_types(s, false).sphere_types; n > 31) {
    throw InputError(where + "bodies: " + peer + ": " + std::to_string(n) +
                     " kinds of free sphere (material" +
                     (s.contact.law == scene::ContactLaw::linear ? " and mass" : "") +
                     "): one group each, and the code holds 32 groups");
  }
  if (s.contact.law == scene::ContactLaw::potential) {
    throw InputError(where + "contact.law: " + peer +
                     ": \"potential\" (Munjiza) has no counterpart in its granular pair styles");
  }
}

AxisPlane axis_plane(const scene::PlaneShape& p) {
  const Vec3 n = p.normal.normalized();
  AxisPlane out;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(std::abs(n[a]) - 1) < 1e-12) {
      out.axis = a;
      out.at = p.point[a];
      out.positive = n[a] > 0;
    }
  }
  return out;
}

double mass_eff(const scene::SceneDef& s, int sphere, int other) {
  const bool ball = std::holds_alternative<scene::SphereShape>(s.bodies[other].shape);
  return effective_mass(
      scene::sphere_mass(s, sphere),
      ball ? scene::sphere_mass(s, other) : std::numeric_limits<double>::infinity());
}

namespace {
scene::PairConstants pair_of(const scene::SceneDef& s, int a, int b) {
  return scene::pair_constants(s.contact, s.materials[s.bodies[a].material],
                               s.materials[s.bodies[b].material]);
}
}  // namespace

double pair_zeta(const scene::SceneDef& s, int a, int b) {
  return pair_of(s, a, b).zeta;
}
double pair_young_eff(const scene::SceneDef& s, int a, int b) {
  return pair_of(s, a, b).young_eff;
}
double pair_shear_eff(const scene::SceneDef& s, int a, int b) {
  return pair_of(s, a, b).shear_eff;
}
double pair_friction(const scene::SceneDef& s, int a, int b) {
  if (s.contact.law == scene::ContactLaw::hertz) return 0;  // no tangential force
  return pair_of(s, a, b).friction;
}

std::string num(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

Types atom_types(const scene::SceneDef& s, bool typed_planes) {
  Types t;
  t.spheres = free_spheres(s);
  const bool linear = s.contact.law == scene::ContactLaw::linear;
  std::vector<std::pair<int, double>> keys;  // (material, mass under linear) of each type
  for (int b : t.spheres) {
    const std::pair<int, double> key{s.bodies[b].material, linear ? scene::sphere_mass(s, b) : 0.0};
    std::size_t k = 0;
    while (k < keys.size() && keys[k] != key) ++k;
    if (k == keys.size()) {
      keys.push_back(key);
      t.body.push_back(b);
    }
    t.of_sphere.push_back(static_cast<int>(k) + 1);
  }
  t.sphere_types = static_cast<int>(keys.size());
  for (int b = 0; b < static_cast<int>(s.bodies.size()); ++b) {
    if (!std::holds_alternative<scene::PlaneShape>(s.bodies[b].shape)) continue;
    t.planes.push_back(b);
    if (typed_planes) t.body.push_back(b);
  }
  return t;
}

void check_damping(const scene::SceneDef& s, const char* peer, double zeta_min, double zeta_max,
                   const std::string& reach) {
  if (s.contact.law == scene::ContactLaw::linear) return;
  for (std::size_t a = 0; a < s.bodies.size(); ++a) {
    for (std::size_t b = a + 1; b < s.bodies.size(); ++b) {
      const double z = pair_zeta(s, static_cast<int>(a), static_cast<int>(b));
      if (z >= zeta_max || (z > 0 && z < zeta_min)) {
        throw InputError(s.file.string() + ": restitution: " + peer + ": bodies \"" +
                         s.bodies[a].name + "\" and \"" + s.bodies[b].name +
                         "\" need the Hertz damping ζ = " + num(z) + ", " + reach);
      }
    }
  }
}

std::string data_file(const scene::SceneDef& s, const Types& types, double duration) {
  // The box holds every sphere over the run (boundary m m m shrink-wraps beyond it anyway).
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (int k : types.spheres) {
    const scene::BodyDef& b = s.bodies[k];
    const double rad = std::get<scene::SphereShape>(b.shape).radius;
    const Vec3 end = b.position + b.velocity * duration;
    lo = lo.cwiseMin(b.position.cwiseMin(end) - Vec3::Constant(2 * rad));
    hi = hi.cwiseMax(b.position.cwiseMax(end) + Vec3::Constant(2 * rad));
  }
  std::ostringstream o;
  o << "asperity scene " << s.name << "\n\n"
    << types.spheres.size() << " atoms\n"
    << types.body.size() << " atom types\n"
    << num(lo.x()) << ' ' << num(hi.x()) << " xlo xhi\n"
    << num(lo.y()) << ' ' << num(hi.y()) << " ylo yhi\n"
    << num(lo.z()) << ' ' << num(hi.z()) << " zlo zhi\n\nAtoms\n\n";
  for (std::size_t k = 0; k < types.spheres.size(); ++k) {
    const scene::BodyDef& b = s.bodies[types.spheres[k]];
    // atom-ID atom-type diameter density x y z (atom_style sphere / granular)
    o << k + 1 << ' ' << types.of_sphere[k] << ' '
      << num(2 * std::get<scene::SphereShape>(b.shape).radius) << ' '
      << num(s.materials[b.material].density) << ' ' << num(b.position.x()) << ' '
      << num(b.position.y()) << ' ' << num(b.position.z()) << "\n";
  }
  o << "\nVelocities\n\n";
  for (std::size_t k = 0; k < types.spheres.size(); ++k) {
    const scene::BodyDef& b = s.bodies[types.spheres[k]];
    o << k + 1 << ' ' << num(b.velocity.x()) << ' ' << num(b.velocity.y()) << ' '
      << num(b.velocity.z()) << ' ' << num(b.angular_velocity.x()) << ' '
      << num(b.angular_velocity.y()) << ' ' << num(b.angular_velocity.z()) << "\n";
  }
  return o.str();
}

std::string atoms_block(const scene::SceneDef& s, const Types& types) {
  std::ostringstream o;
  o << "read_data atoms.data\n";
  double rmin = 1e300;
  for (int b : types.spheres)
    rmin = std::min(rmin, std::get<scene::SphereShape>(s.bodies[b].shape).radius);
  for (int k = 1; k <= types.sphere_types; ++k) o << "group t" << k << " type " << k << "\n";
  // Skin: half the smallest radius, checked every step (a pair is never missed).
  o << "neighbor " << num(0.5 * rmin) << " bin\nneigh_modify delay 0 every 1 check yes\n";
  return o.str();
}

namespace {

// A dump written with `dump custom 1 ... id x y z vx vy vz fx fy fz omegax omegay omegaz EXTRA...`
// and `dump_modify sort id`: one sample per step. `force` turns one sample's atom rows (in id
// order; columns as listed, id first) into the recorded body's contact force.
PeerTrace read_dump(const fs::path& file, int atoms, double dt,
                    const std::function<Vec3(const std::vector<std::vector<double>>&)>& force,
                    const std::string& peer) {
  std::ifstream in(file);
  if (!in) throw PeerFailure(peer + ": " + file.string() + " was not written");
  PeerTrace tr;
  std::string line;
  std::vector<std::vector<double>> rows(static_cast<std::size_t>(atoms));
  std::vector<Vec3> last_w(static_cast<std::size_t>(atoms), Vec3::Zero());
  while (std::getline(in, line)) {
    if (line.rfind("ITEM: TIMESTEP", 0) != 0) continue;
    std::getline(in, line);
    const double step = std::strtod(line.c_str(), nullptr);
    while (std::getline(in, line) && line.rfind("ITEM: ATOMS", 0) != 0) {
    }
    for (int a = 0; a < atoms; ++a) {
      if (!std::getline(in, line))
        throw PeerFailure(peer + ": " + file.string() + ": truncated at step " + num(step));
      std::istringstream cols(line);
      rows[a].clear();
      for (double v; cols >> v;) rows[a].push_back(v);
      if (rows[a].size() < 13)
        throw PeerFailure(peer + ": " + file.string() + ": unreadable row \"" + line + "\"");
    }
    tr.t.push_back(step * dt);
    tr.force.push_back(force(rows));
    tr.x.emplace_back();
    tr.v.emplace_back();
    for (int a = 0; a < atoms; ++a) {
      const auto& r = rows[a];
      tr.x.back().emplace_back(r[1], r[2], r[3]);
      tr.v.back().emplace_back(r[4], r[5], r[6]);
      last_w[a] = Vec3(r[10], r[11], r[12]);
    }
  }
  tr.final_w = last_w;
  return tr;
}

// The last `run` of a log into tr: its wall seconds ("Loop time of T on 1 procs") and CPU seconds
// (T times its "% CPU use"; LIGGGHTS 3.8 prints no such line: cpu_measured false, CPU = T). Throws
// PeerFailure when there is no loop time.
void read_loop_time(const fs::path& log, PeerTrace& tr, const std::string& peer) {
  std::ifstream in(log);
  double loop = -1, cpu_use = -1;
  for (std::string line; std::getline(in, line);) {
    double t = 0;
    if (std::sscanf(line.c_str(), "Loop time of %lf", &t) == 1) {
      loop = t;
      cpu_use = -1;
    }
    double pct = 0;
    if (std::sscanf(line.c_str(), "%lf%% CPU use", &pct) == 1) cpu_use = pct;
  }
  if (loop < 0) throw PeerFailure(peer + ": " + log.string() + ": no \"Loop time\" line");
  tr.wall_seconds = loop;
  tr.cpu_measured = cpu_use >= 0;
  tr.cpu_seconds = tr.cpu_measured ? loop * cpu_use / 100 : loop;
}

// The version line of a log (its first line).
std::string log_version(const fs::path& log) {
  std::ifstream in(log);
  std::string line;
  std::getline(in, line);
  return line;
}

// Runs `exe -in input -log log -screen none` in `dir`; throws PeerFailure with the log's ERROR
// line (or its tail) when it fails.
void run_input(const fs::path& exe, const fs::path& dir, const std::string& input_name,
               const std::string& log_name, const std::string& peer) {
  const std::string cmd = "cd " + shell_quote(dir.string()) + " && " + shell_quote(exe.string()) +
                          " -in " + input_name + " -log " + log_name + " -screen none > " +
                          shell_quote(peer + ".out") + " 2>&1 < /dev/null";
  const int code = run_command(cmd);
  if (code != 0) {
    std::string why;
    for (const std::string& f : {log_name, peer + ".out"}) {
      std::ifstream in(dir / f);
      for (std::string line; std::getline(in, line);) {
        if (line.rfind("ERROR", 0) == 0) why = line;
      }
      if (!why.empty()) break;
    }
    if (why.empty()) why = log_tail(dir / (peer + ".out"));
    throw PeerFailure(peer + " failed (exit " + std::to_string(code) + "): " + why +
                      " [log: " + (dir / log_name).string() + "]");
  }
}

// The motion and the run: gravity, velocity Verlet, the step, the dump (trace only).
std::string motion(const Dialect& d, const scene::SceneDef& s, const Resolved& r, bool trace,
                   const std::vector<std::string>& plane_force) {
  std::ostringstream o;
  const double g = s.gravity.norm();
  if (g > 0) {
    const Vec3 dir = s.gravity / g;
    o << "fix gravity all gravity " << num(g) << " vector " << num(dir.x()) << ' ' << num(dir.y())
      << ' ' << num(dir.z()) << "\n";
  }
  o << "fix integrate all nve/sphere\ntimestep " << num(r.dt) << "\nthermo " << r.steps << "\n";
  if (trace) {
    o << "dump trace all custom 1 trace.dump id x y z vx vy vz fx fy fz omegax omegay omegaz";
    for (const auto& c : plane_force) o << ' ' << c;
    o << "\ndump_modify trace sort id format ";
    if (d.line_format) {
      o << "\"%d";
      for (std::size_t c = 0; c < 12 + plane_force.size(); ++c) o << " %.17g";
      o << "\"\n";
    } else {
      o << "float %.17g\n";
    }
  }
  o << "run " << r.steps << "\n";
  return o.str();
}

}  // namespace

PeerTrace run(const Dialect& d, const scene::SceneDef& s, const Resolved& r, const fs::path& exe,
              const fs::path& dir, RunMode mode) {
  const Types types = atom_types(s, d.typed_planes);
  std::vector<std::string> plane_force;
  const std::string setup = d.setup(s, types, plane_force);
  write_file(dir / "atoms.data", data_file(s, types, static_cast<double>(r.steps) * r.dt));
  write_file(dir / "in.timing", setup + motion(d, s, r, false, plane_force));
  run_input(exe, dir, "in.timing", "timing.log", d.peer);
  PeerTrace tr;
  if (mode == RunMode::trace) {
    write_file(dir / "in.trace", setup + motion(d, s, r, true, plane_force));
    run_input(exe, dir, "in.trace", "trace.log", d.peer);
    const int rec = s.record.body;
    const bool rec_is_plane = std::holds_alternative<scene::PlaneShape>(s.bodies[rec].shape);
    std::size_t rec_atom = 0;
    for (std::size_t k = 0; k < types.spheres.size(); ++k)
      if (types.spheres[k] == rec) rec_atom = k;
    const double rec_mass = rec_is_plane ? 0.0 : scene::sphere_mass(s, rec);
    auto force = [&](const std::vector<std::vector<double>>& rows) -> Vec3 {
      if (rec_is_plane) {
        Vec3 f = Vec3::Zero();
        for (const auto& row : rows) {
          for (std::size_t c = 13; c + 2 < row.size(); c += 3)
            f -= Vec3(row[c], row[c + 1], row[c + 2]);
        }
        return f;
      }
      const auto& row = rows[rec_atom];
      return Vec3(row[7], row[8], row[9]) - rec_mass * s.gravity;
    };
    tr = read_dump(dir / "trace.dump", static_cast<int>(types.spheres.size()), r.dt, force, d.peer);
  }
  read_loop_time(dir / "timing.log", tr, d.peer);
  tr.version = log_version(dir / "timing.log");
  return tr;
}

}  // namespace asperity::peers::lammps_family
