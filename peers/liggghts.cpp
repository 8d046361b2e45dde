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
// Free spheres share an atom type when their coefficients coincide (lammps_family::atom_types),
// every plane is a type of its own, so m* and each coefficient is exact per pair.
#include <cmath>
#include <numbers>
#include <sstream>

#include "peers/lammps_family.hpp"
#include "peers/peer_adapters.hpp"
#include "solver/scene/resolve.hpp"

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
  lammps_family::check_damping(s, "liggghts", 0.0, kZetaMax,
                               "beyond what LIGGGHTS's β = ln e/√(ln²e + π²) reaches with its e > "
                               "0.05 (ζ = √5|β| < 1.543)");
}

// The restitution whose LIGGGHTS β gives ζ = √5 |β|.
double liggghts_e_for(double zeta) {
  const double beta = zeta / std::sqrt(5.0);
  return std::exp(-std::numbers::pi * beta / std::sqrt(1 - beta * beta));
}

// Atoms, per-type and per-type-pair properties, one primitive wall per plane (its own type).
std::string setup(const scene::SceneDef& s, const lammps_family::Types& types,
                  std::vector<std::string>& plane_force) {
  using namespace lammps_family;
  const std::vector<int>& walls = types.planes;
  const std::vector<int>& body_of_type = types.body;  // type k + 1 -> scene body
  const int nt = static_cast<int>(body_of_type.size());
  const bool linear = s.contact.law == scene::ContactLaw::linear;

  std::ostringstream o;
  o << "# asperity scene \"" << s.name << "\" (peers/liggghts.cpp writes this file)\n"
    << "units si\nhard_particles yes\natom_style granular\natom_modify map array\n"
    << "boundary m m m\nnewton off\ncommunicate single vel yes\n"
    << atoms_block(s, types);
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
    const double kn = *s.contact.kn, kt = scene::linear_kt(s.contact);
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
  for (std::size_t k = 0; k < walls.size(); ++k) {
    const AxisPlane p = axis_plane(std::get<scene::PlaneShape>(s.bodies[walls[k]].shape));
    std::ostringstream fix_id;
    fix_id << 'w' << k;
    const std::string id = fix_id.str();
    o << "fix " << id << " all wall/gran model " << model << " tangential history primitive type "
      << types.sphere_types + static_cast<int>(k) + 1 << ' ' << axis_name[p.axis] << ' '
      << num(p.at) << " store_force yes limitForce on\n";
    if (walls[k] == s.record.body) {
      for (int c = 1; c <= 3; ++c) {
        std::ostringstream col;
        col << "f_force_" << id << '[' << c << ']';
        plane_force.push_back(col.str());
      }
    }
  }
  return o.str();
}

PeerTrace run(const scene::SceneDef& s, const Resolved& r, const fs::path& exe, const fs::path& dir,
              RunMode mode) {
  static constexpr lammps_family::Dialect dialect{
      .peer = "liggghts", .typed_planes = true, .line_format = true, .setup = setup};
  return lammps_family::run(dialect, s, r, exe, dir, mode);
}

}  // namespace

Adapter liggghts_adapter() {
  return {.name = "liggghts",
          .program = "liggghts",
          .package = "liggghts",
          .cpu_note =
              "LIGGGHTS's loop time (one process, one thread), a run without the dump: "
              "wall time, the only clock it prints",
          .check = check,
          .run = run};
}

}  // namespace asperity::peers
