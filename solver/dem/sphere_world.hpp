// Rigid-sphere DEM world: spheres against spheres, planes and fixed boxes, plain arrays (SoA).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "solver/contact/hertz_mindlin.hpp"
#include "solver/contact/pair_constants.hpp"
#include "solver/contact/restitution_damping.hpp"
#include "solver/core/body_contacts.hpp"
#include "solver/core/energy.hpp"
#include "solver/core/material.hpp"
#include "solver/core/profile.hpp"
#include "solver/core/vec.hpp"

namespace asperity::dem {

enum class WallKind : std::uint8_t { plane, box };

// A fixed wall. Plane: a = point, b = unit normal into the free side. Box: a = min, b = max.
struct Wall {
  WallKind kind = WallKind::plane;
  Vec3 a = Vec3::Zero();
  Vec3 b = Vec3::Zero();
  int material = 0;
  int body = -1;  // scene body index
};

struct LawDef {
  contact::NormalLaw normal = contact::NormalLaw::hertz;
  bool tangential = true;  // hertz-mindlin and linear carry a tangential spring; hertz does not
  double kn = 0;           // linear only, N/m
  double kt = 0;           // linear only, N/m
  std::optional<double> friction;     // overrides the pair's
  std::optional<double> restitution;  // overrides the pair's
};

// One sphere–sphere pair of the neighbour list; its history is in PairHistory.
struct PairContact {
  int i = 0, j = 0;  // i < j
  int law = 0;       // its constants: SphereWorld::laws[law]
};

// The history of the candidate pairs (zero while apart), one column per component, in the order
// of SphereWorld::pairs: the Hertz–Mindlin loop reads and writes a batch of it in place.
struct PairHistory {
  std::vector<double> spring[3];  // tangential spring, N
  std::vector<double> viscous;    // last non-elastic normal force (dashpot, clipping), N

  Vec3 spring_of(std::size_t k) const { return {spring[0][k], spring[1][k], spring[2][k]}; }
  void resize(std::size_t n) {
    for (std::vector<double>& c : spring) c.assign(n, 0.0);
    viscous.assign(n, 0.0);
  }
};

// The constants of a candidate pair, set when the neighbour list is built: the Hertz(–Mindlin)
// coefficients of its material pair, two radii and masses, so that the force loop takes no square
// root or quotient that is the same every step (the linear law has its own few and takes them from
// the material pair). Pairs that share all of these share one entry (a packing of one size and
// material has one): 64 bytes per kind of pair instead of per pair, which the loop reads every
// step.
struct PairLaw {
  contact::HertzMindlinCoefficients hertz;
  double inv_min_radius = 0;  // 1 / the smaller radius, 1/m (the pass-through check)
};

// One sphere–wall history slot (index wall * n_spheres + sphere).
struct WallContact {
  Vec3 spring = Vec3::Zero();
  double viscous = 0;
};

// Material-pair constants, set once by initialise from contact::pair_constants (index
// a * n_materials + b): its fields but the restitution, which the force loop does not read.
struct PairConstants {
  double young_eff = 0;
  double shear_eff = 0;
  double friction = 0;
  double zeta = 0;  // damping realising the pair restitution
};

struct SphereWorld {
  // Sphere state (columns are spheres).
  // No orientation: a sphere's contacts and outputs do not depend on it (its spin does).
  Eigen::Matrix3Xd x, v, w;                   // position m, velocity m/s, angular velocity rad/s
  Eigen::Matrix3Xd force, torque;             // this step's totals, without gravity
  Eigen::Matrix3Xd v_end;                     // predicted end-of-step velocity the dashpots use
  std::vector<double> radius, mass, inertia;  // m, kg, kg·m² (2/5 m r²)
  std::vector<double> inv_mass, inv_inertia;  // 1/kg, 1/(kg·m²): set by initialise
  std::vector<int> material, body;            // material index, scene body index
  std::vector<std::uint8_t> fixed;

  std::vector<Material> materials;
  std::vector<PairConstants> pair;
  std::vector<Wall> walls;
  Vec3 gravity = Vec3::Zero();
  LawDef law;

  // Broad phase: Verlet neighbour list, rebuilt when a sphere moved more than skin/2.
  double skin = 0;
  std::vector<PairContact> pairs;
  PairHistory history;        // of pairs[k], at k
  std::vector<PairLaw> laws;  // the distinct constants of the candidate pairs (PairContact::law)
  Eigen::Matrix3Xd x_at_build;
  long rebuilds = 0;
  std::vector<WallContact> wall_contacts;

  // Bookkeeping.
  Eigen::Matrix3Xd x_initial;    // gravity potential is measured from here
  double dissipated = 0;         // J, accumulated
  long contact_updates = 0;      // pair evaluations with positive overlap, accumulated
  double max_overlap_ratio = 0;  // largest overlap / smaller radius seen; > 1: passed through

  // This step's contact output per scene body (spheres and walls alike; core/body_contacts.hpp).
  BodyContacts contacts;

  double time = 0;
  long steps = 0;
  Profile profile;

  int size() const { return static_cast<int>(radius.size()); }
};

// Sets derived constants, the neighbour list and the initial forces. Call once after filling
// the sphere arrays, materials, walls and law.
void initialise(SphereWorld& world);

// One velocity-Verlet step: half kick, drift, broad phase, contact forces, half kick.
void step(SphereWorld& world, double dt);

// Kinetic (translation and rotation), contact, gravity and dissipated terms; no elastic term.
// The contact energy (the elastic energy stored in the touching contacts at the current positions
// and springs) is computed here, when asked, not in every step.
EnergyBalance energy(const SphereWorld& world);

// Bytes the world's arrays hold (their capacity): the solver's state apart from the scene it was
// built from (summary.json `state_bytes`).
std::size_t state_bytes(const SphereWorld& world);

}  // namespace asperity::dem
