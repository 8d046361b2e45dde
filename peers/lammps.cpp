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
// Free spheres share an atom type when their coefficients coincide (lammps_family::atom_types: a
// material; under linear, a material and a mass), so every coefficient is exact per pair. A plane
// is a fix wall/gran per sphere type (R* = r: a flat wall's radius is infinite there).
#include <cmath>
#include <sstream>

#include "peers/lammps_family.hpp"
#include "peers/peer_adapters.hpp"
#include "solver/scene/resolve.hpp"

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
  lammps_family::check_damping(s, "lammps", kAlphaMin, kAlphaMax,
                               "outside what LAMMPS's Tsuji map α(e) reaches (0.0003 to 1.2728)");
}

// The pair_coeff / fix wall/gran model words for the contact of sphere a with body b.
std::string model(const scene::SceneDef& s, int a, int b) {
  using namespace lammps_family;
  const double zeta = pair_zeta(s, a, b), m = mass_eff(s, a, b), mu = pair_friction(s, a, b);
  std::ostringstream o;
  if (s.contact.law == scene::ContactLaw::linear) {
    const double kn = *s.contact.kn, kt = scene::linear_kt(s.contact);
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

// Atoms, pair coefficients per pair of sphere types, one fix wall/gran per plane and sphere type.
std::string setup(const scene::SceneDef& s, const lammps_family::Types& types,
                  std::vector<std::string>& plane_force) {
  using namespace lammps_family;
  const int n = types.sphere_types;
  const auto& rep = types.body;  // a sphere of each type
  std::ostringstream o;
  o << "# asperity scene \"" << s.name << "\" (peers/lammps.cpp writes this file)\n"
    << "units si\natom_style sphere\natom_modify map array\nboundary m m m\nnewton off\n"
    << "comm_modify vel yes\n";
  o << atoms_block(s, types) << "pair_style granular\n";
  for (int i = 0; i < n; ++i) {
    for (int j = i; j < n; ++j)
      o << "pair_coeff " << i + 1 << ' ' << j + 1 << ' ' << model(s, rep[i], rep[j]) << "\n";
  }
  const char* axis_name[] = {"xplane", "yplane", "zplane"};
  for (int w : types.planes) {
    const AxisPlane p = axis_plane(std::get<scene::PlaneShape>(s.bodies[w].shape));
    for (int k = 0; k < n; ++k) {
      std::ostringstream fix_id;  // (string operator+ here trips GCC 12's -Wrestrict)
      fix_id << 'w' << w << '_' << k + 1;
      const std::string id = fix_id.str();
      o << "fix " << id << " t" << k + 1 << " wall/gran granular " << model(s, rep[k], w) << ' '
        << axis_name[p.axis] << ' ' << (p.positive ? num(p.at) : "NULL") << ' '
        << (p.positive ? "NULL" : num(p.at)) << " contacts\n";
      if (w == s.record.body) {
        for (int c = 2; c <= 4; ++c) {
          std::ostringstream col;
          col << "f_" << id << '[' << c << ']';
          plane_force.push_back(col.str());
        }
      }
    }
  }
  return o.str();
}

PeerTrace run(const scene::SceneDef& s, const Resolved& r, const fs::path& exe, const fs::path& dir,
              RunMode mode) {
  static constexpr lammps_family::Dialect dialect{
      .peer = "lammps", .typed_planes = false, .line_format = false, .setup = setup};
  return lammps_family::run(dialect, s, r, exe, dir, mode);
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
