// The LIGGGHTS adapter (Debian's `liggghts`, LIGGGHTS-PUBLIC 3.8.0): `pair_style gran` and
// `fix wall/gran ... primitive` with the true materials (docs/crosscheck.md, "LIGGGHTS"):
//   hertz, hertz-mindlin  model hertz (k_n = 4/3 Y* √(R*δ): Y*, G* mixed as asperity's E*, G*;
//                         a primitive wall's R* is the sphere's r, measured) with tangential
//                         history (k_t = 8 G* a on the total tangential displacement); hertz: μ = 0
//   damping               γ_n = 2√(5/6) β √(S_n m*), S_n = 2Y*√(R*δ), β = ln e/√(ln²e + π²): with
//                         S_n = 3/2 K δ^½ this is asperity's ζ√(m* K) δ^¼ for ζ = √5 |β|, and
//                         its tangential dashpot 2√(5/6) β √(S_t m*) is asperity's ζ√(m* k_t/1.5).
//                         The restitution handed to LIGGGHTS is the e whose β gives ζ (not the
//                         target e: LIGGGHTS's log map realises another e for a clipped Hertz
//                         dashpot); limitForce on clips the normal force at zero as asperity does
//   linear                model hooke/stiffness with k_n, k_t, γ_n = ζ√(k_n/m*), γ_t = ζ√(k_t/m*)
//                         per pair of atom types (its damping is γ m* v)
// Every free sphere and every plane is its own atom type, so m* and each coefficient is per pair.
#include <cmath>
#include <numbers>
#include <sstream>

#include "core/error.hpp"
#include "lammps_family.hpp"
#include "peer_adapters.hpp"

namespace asperity::peers {
namespace {
namespace fs = std::filesystem;
using lammps_family::num;

// ζ = √5 |β|, and LIGGGHTS requires e > 0.05 (global_properties.cpp): |β(0.05)| = 0.690.
const double kZetaMax =
    std::sqrt(5.0) * -std::log(0.05) /
    std::sqrt(std::log(0.05) * std::log(0.05) + std::numbers::pi * std::numbers::pi);

void check(const scene::SceneDef& s) {
  lammps_family::check_common(s, "liggghts");
  if (s.contact.law == scene::ContactLaw::linear) return;
  for (std::size_t a = 0; a < s.bodies.size(); ++a) {
    for (std::size_t b = a + 1; b < s.bodies.size(); ++b) {
      const double z = lammps_family::pair_zeta(s, static_cast<int>(a), static_cast<int>(b));
      if (z >= kZetaMax) {
        throw InputError(s.file.string() + ": restitution: liggghts: bodies \"" + s.bodies[a].name +
                         "\" and \"" + s.bodies[b].name +
                         "\" need the Hertz damping ζ = " + num(z) +
                         ", beyond what LIGGGHTS's β = ln e/√(ln²e + π²) reaches with its e > 0.05 "
                         "(ζ = √5|β| < 1.543)");
      }
    }
  }
}

// The restitution whose LIGGGHTS β gives ζ = √5 |β|.
double liggghts_e_for(double zeta) {
  const double beta = zeta / std::sqrt(5.0);
  return std::exp(-std::numbers::pi * beta / std::sqrt(1 - beta * beta));
}

std::string input(const scene::SceneDef& s, const Resolved& r, bool trace) {
  using namespace lammps_family;
  const std::vector<int> spheres = free_spheres(s);
  std::vector<int> walls;
  for (int b = 0; b < static_cast<int>(s.bodies.size()); ++b)
    if (std::holds_alternative<scene::PlaneShape>(s.bodies[b].shape)) walls.push_back(b);
  std::vector<int> body_of_type = spheres;  // type k + 1 -> scene body
  body_of_type.insert(body_of_type.end(), walls.begin(), walls.end());
  const int nt = static_cast<int>(body_of_type.size());
  const bool linear = s.contact.law == scene::ContactLaw::linear;

  std::ostringstream o;
  o << "# asperity scene \"" << s.name << "\" (validation/peers/liggghts.cpp writes this file)\n"
    << "units si\nhard_particles yes\natom_style granular\natom_modify map array\n"
    << "boundary m m m\nnewton off\ncommunicate single vel yes\n"

    << atoms_block(s, spheres);
  auto per_type = [&](const char* name, auto value) {
    o << "fix m_" << name << " all property/global " << name << " peratomtype";
    for (int b : body_of_type) o << ' ' << num(value(s.materials[s.bodies[b].material]));
    o << "\n";
  };
  // A per-pair property: value(sphere, other) for every pair of types with a sphere; two planes
  // never meet, so theirs is `none`.
  auto per_pair = [&](const char* name, auto value, double none) {
    o << "fix m_" << name << " all property/global " << name << " peratomtypepair " << nt;
    for (int i = 0; i < nt; ++i) {
      for (int j = 0; j < nt; ++j) {
        const int a = body_of_type[static_cast<std::size_t>(i)];
        const int b = body_of_type[static_cast<std::size_t>(j)];
        auto sphere = [&](int k) {
          return std::holds_alternative<scene::SphereShape>(
              s.bodies[static_cast<std::size_t>(k)].shape);
        };
        o << ' ' << num(sphere(a) ? value(a, b) : sphere(b) ? value(b, a) : none);
      }
    }
    o << "\n";
  };
  per_type("youngsModulus", [](const Material& m) { return m.young; });
  per_type("poissonsRatio", [](const Material& m) { return m.poisson; });
  per_pair(
      "coefficientFriction", [&](int a, int b) { return pair_friction(s, a, b); }, 0.0);
  if (linear) {
    const double kn = *s.contact.kn, kt = s.contact.kt.value_or(2.0 / 7.0 * kn);
    per_pair(
        "kn", [&](int, int) { return kn; }, kn);
    per_pair(
        "kt", [&](int, int) { return kt; }, kt);
    per_pair(
        "gamman",
        [&](int a, int b) { return pair_zeta(s, a, b) * std::sqrt(kn / mass_eff(s, a, b)); }, 0.0);
    per_pair(
        "gammat",
        [&](int a, int b) { return pair_zeta(s, a, b) * std::sqrt(kt / mass_eff(s, a, b)); }, 0.0);
    o << "pair_style gran model hooke/stiffness tangential history limitForce on\n";
  } else {
    per_pair(
        "coefficientRestitution", [&](int a, int b) { return liggghts_e_for(pair_zeta(s, a, b)); },
        1.0);
    o << "pair_style gran model hertz tangential history limitForce on\n";
  }
  o << "pair_coeff * *\n";
  const char* axis_name[] = {"xplane", "yplane", "zplane"};
  const std::string model = linear ? "hooke/stiffness" : "hertz";
  std::vector<std::string> wall_force;
  for (std::size_t k = 0; k < walls.size(); ++k) {
    const AxisPlane p = axis_plane(std::get<scene::PlaneShape>(s.bodies[walls[k]].shape));
    std::ostringstream fix_id;
    fix_id << 'w' << k;
    const std::string id = fix_id.str();
    o << "fix " << id << " all wall/gran model " << model << " tangential history primitive type "
      << spheres.size() + k + 1 << ' ' << axis_name[p.axis] << ' ' << num(p.at)
      << " store_force yes limitForce on\n";
    if (walls[k] == s.record.body) {
      for (int c = 1; c <= 3; ++c) {
        std::ostringstream col;
        col << "f_force_" << id << '[' << c << ']';
        wall_force.push_back(col.str());
      }
    }
  }
  const double g = s.gravity.norm();
  if (g > 0) {
    const Vec3 d = s.gravity / g;
    o << "fix gravity all gravity " << num(g) << " vector " << num(d.x()) << ' ' << num(d.y())
      << ' ' << num(d.z()) << "\n";
  }
  o << "fix integrate all nve/sphere\ntimestep " << num(r.dt) << "\nthermo " << r.steps << "\n";
  if (trace) {
    o << "dump trace all custom 1 trace.dump id x y z vx vy vz fx fy fz omegax omegay omegaz";
    for (const auto& c : wall_force) o << ' ' << c;
    o << "\ndump_modify trace sort id format \"%d";
    for (std::size_t c = 0; c < 12 + wall_force.size(); ++c) o << " %.17g";
    o << "\"\n";
  }
  o << "run " << r.steps << "\n";
  return o.str();
}

PeerTrace run(const scene::SceneDef& s, const Resolved& r, const fs::path& exe,
              const fs::path& dir) {
  using namespace lammps_family;
  const std::vector<int> atoms = free_spheres(s);
  int walls = 0;  // each plane is an atom type of its own (its material)
  for (const scene::BodyDef& b : s.bodies)
    walls += std::holds_alternative<scene::PlaneShape>(b.shape) ? 1 : 0;
  write_file(dir / "atoms.data", data_file(s, atoms, static_cast<int>(atoms.size()) + walls,
                                           static_cast<double>(r.steps) * r.dt));
  write_file(dir / "in.timing", input(s, r, false));
  write_file(dir / "in.trace", input(s, r, true));
  run_input(exe, dir, "in.timing", "timing.log", "liggghts");
  run_input(exe, dir, "in.trace", "trace.log", "liggghts");
  const std::vector<int> spheres = free_spheres(s);
  const int rec = s.record.body;
  const bool rec_is_plane = std::holds_alternative<scene::PlaneShape>(s.bodies[rec].shape);
  int rec_atom = -1;
  for (std::size_t k = 0; k < spheres.size(); ++k)
    if (spheres[k] == rec) rec_atom = static_cast<int>(k);
  const double rec_mass = rec_atom >= 0 ? sphere_mass(s, rec) : 0;
  // A sphere's contact force is its total force less its weight; a plane's is minus the sum of
  // the wall forces its fix stored on the spheres (store_force).
  auto force = [&](const std::vector<std::vector<double>>& rows) -> Vec3 {
    if (rec_is_plane) {
      Vec3 f = Vec3::Zero();
      for (const auto& row : rows)
        if (row.size() >= 16) f -= Vec3(row[13], row[14], row[15]);
      return f;
    }
    const auto& row = rows[static_cast<std::size_t>(rec_atom)];
    return Vec3(row[7], row[8], row[9]) - rec_mass * s.gravity;
  };
  PeerTrace tr =
      read_dump(dir / "trace.dump", static_cast<int>(spheres.size()), r.dt, force, "liggghts");
  tr.cpu_seconds = loop_cpu_seconds(dir / "timing.log", &tr.wall_seconds, "liggghts");
  tr.version = log_version(dir / "timing.log");
  return tr;
}

}  // namespace

Adapter liggghts_adapter() {
  return {.name = "liggghts",
          .program = "liggghts",
          .package = "liggghts",
          .cpu_note = "LIGGGHTS's loop time (one process, one thread), a run without the dump",
          .check = check,
          .run = run};
}

}  // namespace asperity::peers
