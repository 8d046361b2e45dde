// What the LAMMPS and LIGGGHTS adapters share (LIGGGHTS descends from LAMMPS): the per-body
// atom types, the scene checks, the dump reader, the log's timing line.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "peer.hpp"

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

// Effective mass of a free sphere against body b (a plane: the sphere's own mass), kg.
double mass_eff(const scene::SceneDef& s, int sphere, int other);
double sphere_mass(const scene::SceneDef& s, int body);

// The damping ζ asperity uses for the material pair of bodies a and b (its Tsuji or linear form).
double pair_zeta(const scene::SceneDef& s, int a, int b);
// E* and Mindlin's G* of the pair (core/material.hpp), Pa.
double pair_young_eff(const scene::SceneDef& s, int a, int b);
double pair_shear_eff(const scene::SceneDef& s, int a, int b);
double pair_friction(const scene::SceneDef& s, int a, int b);

// The data file (atoms.data) of the free spheres: atom k + 1 of type k + 1, diameter, density,
// position, velocity and spin; its box holds every sphere over `duration`.
std::string data_file(const scene::SceneDef& s, const std::vector<int>& spheres, int types,
                      double duration);

// read_data atoms.data, a group gK per atom, the neighbour settings.
std::string atoms_block(const scene::SceneDef& s, const std::vector<int>& spheres);

// Number format that round-trips a double.
std::string num(double x);

// A dump written with `dump custom 1 ... id x y z vx vy vz fx fy fz omegax omegay omegaz EXTRA...`
// and `dump_modify sort id`: one sample per step. `force` turns one sample's atom rows (in id
// order; columns as listed, id first) into the recorded body's contact force.
PeerTrace read_dump(const std::filesystem::path& file, int atoms, double dt,
                    const std::function<Vec3(const std::vector<std::vector<double>>&)>& force,
                    const std::string& peer);

// CPU seconds of the last `run` in a LAMMPS-family log: "Loop time of T on 1 procs" times its
// "% CPU use" when printed. Throws PeerFailure when absent.
double loop_cpu_seconds(const std::filesystem::path& log, double* wall, const std::string& peer);

// The version line of a LAMMPS-family log (its first line).
std::string log_version(const std::filesystem::path& log);

// Runs `exe -in input -log log -screen none` in `dir`; throws PeerFailure with the log's ERROR
// line (or its tail) when it fails.
void run_input(const std::filesystem::path& exe, const std::filesystem::path& dir,
               const std::string& input_name, const std::string& log_name, const std::string& peer);

}  // namespace asperity::peers::lammps_family
