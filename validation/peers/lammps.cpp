// The LAMMPS adapter (Debian's `lammps`, 29 Sep 2021 update 2, `lmp`): `pair_style granular` and
// `fix wall/gran granular` with coefficients given per pair of bodies, so that LAMMPS computes
// asperity's force law exactly (docs/crosscheck.md, "LAMMPS"):
//   hertz, hertz-mindlin  hertz/material with E = 2E*, ν = 0 (this version's E_eff is E/(2(1−ν²))
//                         between atoms and E/(2(1−ν)) against a wall, measured: with ν = 0 both
//                         give E*); tangential mindlin/force with k_t = 8G* (explicit, so no
//                         mixing: its NULL wall branch gives E(2−ν)(1+ν)/4, measured) — force-
//                         based, incremental, as asperity's spring; hertz: linear_nohistory, μ = 0
//   damping               tsuji (η_n = α√(m* k_n), k_n = 4/3 E* a: asperity's ζ√(m* K)δ^¼ with
//                         α = ζ), the restitution handed to LAMMPS is the e whose Tsuji polynomial
//                         gives α = ζ; x_γt = 2√(G*/E*) makes η_t = ζ√(m* k_t/1.5); limit_damping
//                         clips the normal force at zero as asperity does; e = 1: no damping
//   linear                hooke k_n with η_n = ζ√(m* k_n) (damping velocity, per pair of bodies)
//                         and linear_history k_t with x_γt = √(k_t/k_n)
// Every free sphere is its own atom type, so m* and therefore every coefficient is exact per pair.
// A plane is a fix wall/gran per sphere (R* = r: a flat wall's radius is infinite there).
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "lammps_family.hpp"
#include "peer_adapters.hpp"

namespace asperity::peers {
namespace {
namespace fs = std::filesystem;
using lammps_family::num;

// LAMMPS's Tsuji map α(e) (pair_granular docs), a polynomial fit falling from 1.2728 at e = 0.
double tsuji_alpha(double e) {
  return 1.2728 - 4.2783 * e + 11.087 * e * e - 22.348 * std::pow(e, 3) + 27.467 * std::pow(e, 4) -
         18.022 * std::pow(e, 5) + 4.8218 * std::pow(e, 6);
}
constexpr double kAlphaMax = 1.2728;  // α(0)
constexpr double kAlphaMin = 0.0003;  // α(1): the polynomial does not reach 0

// The restitution to hand LAMMPS so that its α equals asperity's ζ (α falls monotonically).
double tsuji_e_for(double zeta) {
  double lo = 0, hi = 1;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (tsuji_alpha(mid) > zeta ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

void check(const scene::SceneDef& s) {
  lammps_family::check_common(s, "lammps");
  if (s.contact.law == scene::ContactLaw::linear) return;
  for (std::size_t a = 0; a < s.bodies.size(); ++a) {
    for (std::size_t b = a + 1; b < s.bodies.size(); ++b) {
      const double z = lammps_family::pair_zeta(s, static_cast<int>(a), static_cast<int>(b));
      if (z > kAlphaMax || (z > 0 && z < kAlphaMin)) {
        throw InputError(s.file.string() + ": restitution: lammps: bodies \"" + s.bodies[a].name +
                         "\" and \"" + s.bodies[b].name +
                         "\" need the Hertz damping ζ = " + num(z) +
                         ", outside what LAMMPS's Tsuji map α(e) reaches (0.0003 to " + "1.2728)");
      }
    }
  }
}

// The pair_coeff / fix wall/gran model words for the contact of sphere a with body b.
std::string model(const scene::SceneDef& s, int a, int b) {
  using namespace lammps_family;
  const double zeta = pair_zeta(s, a, b), m = mass_eff(s, a, b), mu = pair_friction(s, a, b);
  std::ostringstream o;
  if (s.contact.law == scene::ContactLaw::linear) {
    const double kn = *s.contact.kn, kt = s.contact.kt.value_or(2.0 / 7.0 * kn);
    o << "hooke " << num(kn) << ' ' << num(zeta * std::sqrt(m * kn))
      << " tangential linear_history " << num(kt) << ' ' << num(std::sqrt(kt / kn)) << ' '
      << num(mu) << " damping velocity limit_damping";
    return o.str();
  }
  const double e_star = pair_young_eff(s, a, b), g_star = pair_shear_eff(s, a, b);
  o << "hertz/material " << num(2 * e_star) << ' ' << num(zeta > 0 ? tsuji_e_for(zeta) : 0.0)
    << " 0.0";
  if (s.contact.law == scene::ContactLaw::hertz_mindlin) {
    o << " tangential mindlin/force " << num(8 * g_star) << ' '
      << num(2 * std::sqrt(g_star / e_star)) << ' ' << num(mu);
  } else {
    o << " tangential linear_nohistory 0.0 0.0";
  }
  o << (zeta > 0 ? " damping tsuji" : " damping velocity") << " limit_damping";
  return o.str();
}

std::string input(const scene::SceneDef& s, const Resolved& r, bool trace) {
  using namespace lammps_family;
  const std::vector<int> spheres = free_spheres(s);
  const int n = static_cast<int>(spheres.size());
  std::ostringstream o;
  o << "# asperity scene \"" << s.name << "\" (validation/peers/lammps.cpp writes this file)\n"
    << "units si\natom_style sphere\natom_modify map array\nboundary m m m\nnewton off\n"
    << "comm_modify vel yes\n";
  o << atoms_block(s, spheres) << "pair_style granular\n";
  for (int i = 0; i < n; ++i) {
    for (int j = i; j < n; ++j) {
      o << "pair_coeff " << i + 1 << ' ' << j + 1 << ' '
        << (i == j ? model(s, spheres[i], spheres[i]) : model(s, spheres[i], spheres[j])) << "\n";
    }
  }
  std::vector<std::string> wall_force;  // dump columns of the walls' forces on the spheres
  const char* axis_name[] = {"xplane", "yplane", "zplane"};
  for (int w = 0; w < static_cast<int>(s.bodies.size()); ++w) {
    const auto* pl = std::get_if<scene::PlaneShape>(&s.bodies[w].shape);
    if (!pl) continue;
    const AxisPlane p = axis_plane(*pl);
    for (int k = 0; k < n; ++k) {
      std::ostringstream fix_id;
      fix_id << 'w' << w << '_' << k + 1;
      const std::string id = fix_id.str();
      o << "fix " << id << " g" << k + 1 << " wall/gran granular " << model(s, spheres[k], w) << ' '
        << axis_name[p.axis] << ' ' << (p.positive ? num(p.at) : "NULL") << ' '
        << (p.positive ? "NULL" : num(p.at)) << " contacts\n";
      if (w == s.record.body) {
        for (int c = 2; c <= 4; ++c) {
          std::ostringstream col;
          col << "f_" << id << '[' << c << ']';
          wall_force.push_back(col.str());
        }
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
    o << "\ndump_modify trace sort id format float %.17g\n";
  }
  o << "run " << r.steps << "\n";
  return o.str();
}

PeerTrace run(const scene::SceneDef& s, const Resolved& r, const fs::path& exe,
              const fs::path& dir) {
  using namespace lammps_family;
  // 1. Cost: the plain run, no dump. 2. The trace: the same run dumping every step.
  const std::vector<int> atoms = free_spheres(s);
  write_file(dir / "atoms.data", data_file(s, atoms, static_cast<int>(atoms.size()),
                                           static_cast<double>(r.steps) * r.dt));
  write_file(dir / "in.timing", input(s, r, false));
  write_file(dir / "in.trace", input(s, r, true));
  run_input(exe, dir, "in.timing", "timing.log", "lammps");
  run_input(exe, dir, "in.trace", "trace.log", "lammps");
  const std::vector<int> spheres = free_spheres(s);
  const int rec = s.record.body;
  const bool rec_is_plane = std::holds_alternative<scene::PlaneShape>(s.bodies[rec].shape);
  int rec_atom = -1;
  for (std::size_t k = 0; k < spheres.size(); ++k)
    if (spheres[k] == rec) rec_atom = static_cast<int>(k);
  std::vector<double> mass;
  for (int b : spheres) mass.push_back(sphere_mass(s, b));
  // The recorded body's contact force: a sphere's total force less its weight (fix gravity adds
  // exactly m g); a plane's is minus the sum of what its wall fixes put on the spheres.
  auto force = [&](const std::vector<std::vector<double>>& rows) -> Vec3 {
    if (rec_is_plane) {
      Vec3 f = Vec3::Zero();
      for (const auto& row : rows) {
        for (std::size_t c = 13; c + 2 < row.size(); c += 3)
          f -= Vec3(row[c], row[c + 1], row[c + 2]);
      }
      return f;
    }
    const auto& row = rows[static_cast<std::size_t>(rec_atom)];
    return Vec3(row[7], row[8], row[9]) - mass[static_cast<std::size_t>(rec_atom)] * s.gravity;
  };
  PeerTrace tr =
      read_dump(dir / "trace.dump", static_cast<int>(spheres.size()), r.dt, force, "lammps");
  tr.cpu_seconds = loop_cpu_seconds(dir / "timing.log", &tr.wall_seconds, "lammps");
  tr.version = log_version(dir / "timing.log");
  return tr;
}

}  // namespace

Adapter lammps_adapter() {
  return {.name = "lammps",
          .program = "lmp",
          .package = "lammps",
          .cpu_note = "LAMMPS's loop time times its CPU use, a run without the per-step dump",
          .check = check,
          .run = run};
}

}  // namespace asperity::peers
