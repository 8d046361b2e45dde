// The Hertz–Mindlin law over a batch of sphere contacts held in columns (one array per component
// and quantity), so that the compiler runs it over several contacts per instruction: stage 2 of
// the sphere DEM's staged force loop (dem/sphere_world.cpp, mindlin_pair_forces). Every contact
// gets the bits hertz_contact<true> (dem/hertz_contact.hpp) gives it computed whole.
#pragma once

#include <cstddef>
#include <cstdint>

namespace asperity::dem {

constexpr std::size_t kBatch = 32;  // pairs per batch: its columns stay in L1 (~16 kB)

// A column's length: a batch and a cache line more, so that the columns do not lie a multiple of
// 4 kB apart (loads and stores that far apart wait on each other: 4K aliasing).
constexpr std::size_t kColumn = kBatch + 8;

// What the Hertz–Mindlin law reads and gives of a batch of touching contacts, in columns. Contact
// m: body 1 is sphere i, body 2 sphere j.
struct MindlinColumns {
  // In.
  double d[3][kColumn];                                                   // x_i − x_j, m
  double dist[kColumn], overlap[kColumn];                                 // |d|, reach − |d|, m
  double ri[kColumn], rj[kColumn];                                        // radii, m
  double vi[3][kColumn], wi[3][kColumn], vj[3][kColumn], wj[3][kColumn];  // m/s, rad/s
  double dv_end[3][kColumn];  // v_end,i − v_end,j, m/s
  // The pair's contact::HertzMindlinCoefficients (normal.k, normal.damping, shear, shear_damping,
  // friction) and 1 / the smaller radius (1/m).
  double k[kColumn], damping[kColumn], shear[kColumn], shear_damping[kColumn], friction[kColumn];
  double inv_min_radius[kColumn];
  // Out.
  double force[3][kColumn], normal_force[3][kColumn];  // on sphere i, N
  double torque_i[3][kColumn], torque_j[3][kColumn];   // arm1 × force, arm2 × force, N·m
  double dissipated[kColumn];                          // J
  double ratio[kColumn];                               // overlap / smaller radius
};

// The law over contacts [0, t) of b (t ≤ kBatch), step dt (s). The history (sx, sy, sz: the
// tangential spring, N; viscous: the last non-elastic normal force, N; t each, not overlapping b
// or each other) is read and written in place: contact m's last step's on entry, this step's on
// return.
using MindlinColumnsFn = void (*)(MindlinColumns& b, std::size_t t, double dt, double* sx,
                                  double* sy, double* sz, double* viscous);

// The copies compiled: the baseline's, and on x86-64 with GCC copies for x86-64-v3 (AVX2) and
// x86-64-v4 (AVX-512). No multiply-add is fused in any (mindlin_columns.cpp is compiled with
// -ffp-contract=off), so all give the same bits.
enum class MindlinCopy : std::uint8_t { baseline, x86_64_v3, x86_64_v4 };

// The copy for `copy`, or nullptr where this build has none or this CPU cannot run it.
MindlinColumnsFn mindlin_columns_copy(MindlinCopy copy);

// The copy the force loop runs: the widest this CPU runs (chosen once).
MindlinColumnsFn mindlin_columns();

}  // namespace asperity::dem
