// Shared by the LAMMPS and LIGGGHTS adapters: checks, per-pair constants, dump and log readers.
#include "lammps_family.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>

#include "contact/restitution_damping.hpp"
#include "core/error.hpp"

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

double sphere_mass(const scene::SceneDef& s, int body) {
  const auto& b = s.bodies[body];
  const double r = std::get<scene::SphereShape>(b.shape).radius;
  return s.materials[b.material].density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
}

double mass_eff(const scene::SceneDef& s, int sphere, int other) {
  const double m1 = sphere_mass(s, sphere);
  if (!std::holds_alternative<scene::SphereShape>(s.bodies[other].shape)) return m1;
  const double m2 = sphere_mass(s, other);
  return m1 * m2 / (m1 + m2);
}

double pair_zeta(const scene::SceneDef& s, int a, int b) {
  const Material &ma = s.materials[s.bodies[a].material], &mb = s.materials[s.bodies[b].material];
  const double e = s.contact.restitution.value_or(pair_restitution(ma, mb));
  return contact::damping_for_restitution(s.contact.law == scene::ContactLaw::linear
                                              ? contact::NormalLaw::linear
                                              : contact::NormalLaw::hertz,
                                          e);
}

double pair_young_eff(const scene::SceneDef& s, int a, int b) {
  return effective_young(s.materials[s.bodies[a].material], s.materials[s.bodies[b].material]);
}
double pair_shear_eff(const scene::SceneDef& s, int a, int b) {
  return effective_shear(s.materials[s.bodies[a].material], s.materials[s.bodies[b].material]);
}
double pair_friction(const scene::SceneDef& s, int a, int b) {
  if (s.contact.law == scene::ContactLaw::hertz) return 0;  // no tangential force
  return s.contact.friction.value_or(asperity::pair_friction(s.materials[s.bodies[a].material],
                                                             s.materials[s.bodies[b].material]));
}

std::string num(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string data_file(const scene::SceneDef& s, const std::vector<int>& spheres, int types,
                      double duration) {
  // The box holds every sphere over the run (boundary m m m shrink-wraps beyond it anyway).
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (int k : spheres) {
    const scene::BodyDef& b = s.bodies[k];
    const double rad = std::get<scene::SphereShape>(b.shape).radius;
    const Vec3 end = b.position + b.velocity * duration;
    lo = lo.cwiseMin(b.position.cwiseMin(end) - Vec3::Constant(2 * rad));
    hi = hi.cwiseMax(b.position.cwiseMax(end) + Vec3::Constant(2 * rad));
  }
  std::ostringstream o;
  o << "asperity scene " << s.name << "\n\n"
    << spheres.size() << " atoms\n"
    << types << " atom types\n"
    << num(lo.x()) << ' ' << num(hi.x()) << " xlo xhi\n"
    << num(lo.y()) << ' ' << num(hi.y()) << " ylo yhi\n"
    << num(lo.z()) << ' ' << num(hi.z()) << " zlo zhi\n\nAtoms\n\n";
  for (std::size_t k = 0; k < spheres.size(); ++k) {
    const scene::BodyDef& b = s.bodies[spheres[k]];
    // atom-ID atom-type diameter density x y z (atom_style sphere / granular)
    o << k + 1 << ' ' << k + 1 << ' ' << num(2 * std::get<scene::SphereShape>(b.shape).radius)
      << ' ' << num(s.materials[b.material].density) << ' ' << num(b.position.x()) << ' '
      << num(b.position.y()) << ' ' << num(b.position.z()) << "\n";
  }
  o << "\nVelocities\n\n";
  for (std::size_t k = 0; k < spheres.size(); ++k) {
    const scene::BodyDef& b = s.bodies[spheres[k]];
    o << k + 1 << ' ' << num(b.velocity.x()) << ' ' << num(b.velocity.y()) << ' '
      << num(b.velocity.z()) << ' ' << num(b.angular_velocity.x()) << ' '
      << num(b.angular_velocity.y()) << ' ' << num(b.angular_velocity.z()) << "\n";
  }
  return o.str();
}

std::string atoms_block(const scene::SceneDef& s, const std::vector<int>& spheres) {
  std::ostringstream o;
  o << "read_data atoms.data\n";
  double rmin = 1e300;
  for (std::size_t k = 0; k < spheres.size(); ++k) {
    rmin = std::min(rmin, std::get<scene::SphereShape>(s.bodies[spheres[k]].shape).radius);
    o << "group g" << k + 1 << " id " << k + 1 << "\n";
  }
  // Skin: half the smallest radius, checked every step (a pair is never missed).
  o << "neighbor " << num(0.5 * rmin) << " bin\nneigh_modify delay 0 every 1 check yes\n";
  return o.str();
}

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

double loop_cpu_seconds(const fs::path& log, double* wall, const std::string& peer) {
  std::ifstream in(log);
  double loop = -1, cpu_use = 100;
  for (std::string line; std::getline(in, line);) {
    double t = 0;
    if (std::sscanf(line.c_str(), "Loop time of %lf", &t) == 1) {
      loop = t;
      cpu_use = 100;
    }
    double pct = 0;
    if (std::sscanf(line.c_str(), "%lf%% CPU use", &pct) == 1) cpu_use = pct;
  }
  if (loop < 0) throw PeerFailure(peer + ": " + log.string() + ": no \"Loop time\" line");
  if (wall) *wall = loop;
  return loop * cpu_use / 100;
}

std::string log_version(const fs::path& log) {
  std::ifstream in(log);
  std::string line;
  std::getline(in, line);
  return line;
}

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

}  // namespace asperity::peers::lammps_family
