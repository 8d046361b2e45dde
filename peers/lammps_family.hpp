// What the LAMMPS and LIGGGHTS adapters share (LIGGGHTS descends from LAMMPS): the per-body
// atom types, the scene checks, the dump reader, the log's timing line.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "peers/peer.hpp"

namespace asperity::peers::lammps_family {

// Throws InputError for what neither code's adapter maps (docs/crosscheck.md): non-rigid or mesh
// bodies, the potential law, fixed spheres, boxes, planes whose normal is not ±x, ±y or ±z.
void check_common(const scene::SceneDef& s, const char* peer);

// An axis-aligned plane: axis 0..2, its coordinate, and whether the free side is the + side.
struct AxisPlane {
  int axis = 2;
  double at = 0;
  bool positive = true;
};
AxisPlane axis_plane(const scene::PlaneShape& p);

// Effective mass of a free sphere against body b (a plane: the sphere's own mass), kg (a sphere's
// own mass: scene::sphere_mass, solver/scene/resolve.hpp).
double mass_eff(const scene::SceneDef& s, int sphere, int other);

// The damping ζ asperity uses for the material pair of bodies a and b (its Tsuji or linear form).
double pair_zeta(const scene::SceneDef& s, int a, int b);
// E* and Mindlin's G* of the pair (core/material.hpp), Pa.
double pair_young_eff(const scene::SceneDef& s, int a, int b);
double pair_shear_eff(const scene::SceneDef& s, int a, int b);
double pair_friction(const scene::SceneDef& s, int a, int b);

// Atom types. Free spheres whose every pair coefficient coincides share a type, so that a bed of
// 10,000 spheres of one material is one type (not 10,000 types and 5·10⁷ pair_coeff lines). Both
// codes take a Hertz dashpot's effective mass from the two atoms' masses, so under hertz and
// hertz-mindlin a type is a material; their linear dashpots are given per type pair with m*
// inside (LAMMPS η_n, LIGGGHTS γ_n), so under linear a type is a material and a mass.
struct Types {
  std::vector<int> spheres;    // the free spheres, scene order: atom k + 1 is spheres[k]
  std::vector<int> of_sphere;  // atom type (1-based) of each
  std::vector<int> planes;     // the scene's planes, scene order
  std::vector<int> body;       // type k + 1 -> a body: a sphere of the type, then (typed planes)
                               // each plane
  int sphere_types = 0;
};
// `typed_planes`: each plane is an atom type of its own after the spheres' (LIGGGHTS's primitive
// walls take their material from a type).
Types atom_types(const scene::SceneDef& s, bool typed_planes);

// Throws InputError unless asperity's Hertz damping ζ of every pair of bodies lies in
// [zeta_min, zeta_max) (or is 0): what the peer's restitution map reaches, `reach` saying so.
void check_damping(const scene::SceneDef& s, const char* peer, double zeta_min, double zeta_max,
                   const std::string& reach);

// The data file (atoms.data) of the free spheres: atom k + 1 with its type, diameter, density,
// position, velocity and spin; its box holds every sphere over `duration`.
std::string data_file(const scene::SceneDef& s, const Types& types, double duration);

// read_data atoms.data, a group tK per sphere type, the neighbour settings.
std::string atoms_block(const scene::SceneDef& s, const Types& types);

// How a LAMMPS-family code is driven: the adapter's name, whether its planes are atom types,
// its dump_modify dialect, and its input (pair style, coefficients, walls) up to the motion.
struct Dialect {
  const char* peer;
  bool typed_planes;
  bool line_format;  // LIGGGHTS 3.8 takes one format string for a dump line, not `format float`
  // The input up to the integration: atoms, pair style and coefficients, wall fixes. Appends to
  // `plane_force` the dump columns whose triples sum to minus the recorded plane's force.
  std::string (*setup)(const scene::SceneDef& s, const Types& types,
                       std::vector<std::string>& plane_force);
};

// Runs the scene in the code: atoms.data, in.timing (no dump: the cost) and, for RunMode::trace,
// in.trace (a dump every step, read back as the trace). The recorded body's force: a sphere's
// total force less its weight (fix gravity adds exactly m g), a plane's minus the sum of the
// `plane_force` columns.
PeerTrace run(const Dialect& d, const scene::SceneDef& s, const Resolved& r,
              const std::filesystem::path& exe, const std::filesystem::path& dir, RunMode mode);

// Number format that round-trips a double.
std::string num(double x);

}  // namespace asperity::peers::lammps_family
