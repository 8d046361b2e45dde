// FEM/DEM world: deformable tetrahedral bodies, rigid polyhedra and fixed blocks, in contact by
// Munjiza's distributed potential, under gravity, stepped by explicit central differences.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "solver/contact/munjiza_potential.hpp"
#include "solver/contact/overlap_volume.hpp"
#include "solver/core/body_contacts.hpp"
#include "solver/core/energy.hpp"
#include "solver/core/material.hpp"
#include "solver/core/mesh.hpp"
#include "solver/core/profile.hpp"
#include "solver/core/vec.hpp"
#include "solver/fem/tet_elements.hpp"

namespace asperity::fdem {

enum class BodyKind : std::uint8_t { deformable, rigid, fixed };

// A body to add: its mesh already placed in the world frame (m), its material and motion.
struct BodyDef {
  std::string name;
  BodyKind kind = BodyKind::deformable;
  TetMesh mesh;
  Material material;
  Vec3 velocity = Vec3::Zero();          // m/s (deformable: every node; rigid: the centroid)
  Vec3 angular_velocity = Vec3::Zero();  // rad/s, about the centroid
  // Deformable: damping ratio ξ of the body's highest element mode; make_world turns it into
  // the stiffness-proportional Kelvin–Voigt β = 2ξ/ω_max (TetElements::damping), so lower modes
  // get ξ ω/ω_max (Hughes 2000, §9.3.3). 0: undamped.
  double damping_ratio = 0;
};

// How bodies touch: Munjiza's penalty potential between tetrahedra (every body kind), or an energy
// of the overlap volume between rigid and fixed polyhedra (contact/volume_hertz.hpp,
// contact/volume_linear.hpp, geometry in contact/overlap_volume.hpp).
enum class ContactLaw : std::uint8_t { potential, volume_hertz, volume_linear };

// How a world meets ContactDef::max_contact_factor (issue 11, item 5; fdem/contact_step.hpp, the
// accuracy of each in reports/fem/mesh_step.md):
//   penalty: the one penalty p lowered for every face (limit_penalty);
//   face_penalty: p lowered only on the faces whose nodes set the step, each by what its nodes
//     need (limit_face_penalty): the penalty scaled with the element under it;
//   mass: mass added to the surface nodes whose contact springs set the step (scale_contact_mass).
enum class ContactStepFix : std::uint8_t { penalty, face_penalty, mass };

// Contact parameters.
struct ContactDef {
  ContactLaw law = ContactLaw::potential;
  double kv = 0;  // volume_linear: N/m³
  double kt =
      0;  // volume-linear: the tangential spring of Coulomb friction, N/m (volume-hertz: Mindlin's)
  // p = alpha · E (E the largest Young's modulus among the bodies that are not fixed) unless
  // `penalty` > 0.
  // α = 10: the penetration of a layer of elements pressed together is E/p = 1/10 of their own
  // elastic shortening (Munjiza 2004, eqs 2.56–2.57), while the penalty limits the step by about
  // √α = 3.2 (α = 100 would give 1 % at a 10× smaller step). Against a Hertz contact resolved by
  // elements of size h the extra compliance is about h/(4 α a) of the approach (a the contact
  // radius), a few per cent at a ≈ h: below the mesh error at the resolutions that run in a
  // minute, which is what decides it. A rock's corner strike is harsher: its contact spans an
  // element or less and the peak force at α = 10 is 12–18 % below the stiff-penalty limit even at
  // 1000 surface triangles, and the softer layer of coarse meshes spreads it across resolutions
  // (reports/study/penalty/); the particle-geometry study therefore runs at α = 100.
  double alpha = 10;
  double penalty = 0;   // Pa, overrides alpha when > 0
  double friction = 0;  // Coulomb μ
  // > 0: where the penalty contact would pull a deformable body's predicted step more than this
  // factor below its elements' own limit, contact_step_fix gives way (fdem/contact_step.hpp; issue
  // 11). Scenes that give neither penalty nor penalty_alpha get 2 by face_penalty
  // (run/run_fdem.cpp); 0 (here the default): p as asked.
  double max_contact_factor = 0;
  ContactStepFix contact_step_fix = ContactStepFix::penalty;  // how (above)
  // mass only, > 0: the factor is lowered from max_contact_factor towards 1 as far as the mass
  // added stays within this fraction of every body's mass (scale_contact_mass_within); 0: the
  // factor as given.
  double max_added_mass = 0;
};

struct WorldDef {
  std::vector<BodyDef> bodies;
  ContactDef contact;
  Vec3 gravity = Vec3::Zero();  // m/s²
};

struct Body {
  std::string name;
  BodyKind kind = BodyKind::deformable;
  int node_begin = 0, node_end = 0;  // its nodes in the world arrays
  int elements = -1;                 // deformable: index into World::elements
  int rigid = -1;                    // rigid: index into World::rigid
  double mass = 0;                   // kg (exact, from the tetrahedra)
  Material material;
  // Volume laws: radius of the sphere of the body's volume, m (infinite for a fixed body), which
  // sets the pair's R* (contact/volume_hertz.hpp).
  double radius = 0;
};

// 6-DOF state of a rigid polyhedron; its nodes follow x = c + R r.
struct RigidBody {
  int body = -1;
  Vec3 centre = Vec3::Zero(), velocity = Vec3::Zero(), omega = Vec3::Zero();  // ω in world frame
  Quat orientation = Quat::Identity();
  double mass = 0;
  Mat3 inertia_body = Mat3::Identity();  // about the centre, body frame, kg·m²
  Eigen::Matrix3Xd r_body;               // node offsets in the body frame
  Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
  // Volume laws act on the body as a whole (force, and torque about the centre), not on nodes.
  Vec3 volume_force = Vec3::Zero(), volume_torque = Vec3::Zero();
  Vec3 centre_initial = Vec3::Zero();
};

// One candidate pair of surface tetrahedra (indices into World::surface_tets), with the
// tangential-spring history of its friction.
struct TetPair {
  int a = 0, b = 0;
  Vec3 spring = Vec3::Zero();
};

// Volume laws: the overlap integrals of one pair of bodies, gathered over their candidate
// tetrahedron pairs during a step (contact/overlap_volume.hpp).
struct BodyOverlap {
  int a = -1, b = -1;  // bodies, a < b
  Vec3 origin = Vec3::Zero();
  contact::OverlapSide side_a, side_b;  // ∂A ∩ B and ∂B ∩ A
  double energy = 0;                    // J: W(V), or volume-linear's work done so far
  double volume = 0;                    // V at the last step, m³
  double slope = 0;                     // s = |F| / |S| at the last step, Pa
  Vec3 spring = Vec3::Zero();           // friction: the tangential spring force on a, N
};

#include "solver/contact/overlap_volume.hpp"
struct World {
  // Nodes, structure of arrays. Fixed nodes have mass 0 and inverse mass 0.
  Eigen::Matrix3Xd x, v, f;    // m, m/s, N (contact + internal, without gravity)
  Eigen::Matrix3Xd x_initial;  // gravity potential is measured from here
  // The contact part of f, node by node (N), kept only while keep_contact_force is set (frames
  // for ParaView, run/vtk_series.hpp): a copy, so keeping it changes no result.
  Eigen::Matrix3Xd f_contact;
  bool keep_contact_force = false;
  std::vector<double> mass, inv_mass;
  std::vector<int> node_body;

  std::vector<Body> bodies;
  std::vector<fem::TetElements> elements;
  std::vector<RigidBody> rigid;
  Vec3 gravity = Vec3::Zero();

  // Contact: surface-adjacent tetrahedra (a node on the body's surface; under a volume law every
  // tetrahedron, so that a surface triangle deep in the other body is still clipped), their body,
  // and per-surface-face data for the time step.
  Eigen::Matrix4Xi surface_tets;
  std::vector<int> surface_tet_body;
  // Largest centroid-to-face height of each surface tetrahedron, 3V/(4 A_min), in the reference
  // configuration, m: how deep a point can go into its potential before reaching the centroid.
  std::vector<double> surface_tet_height;
  double penalty = 0;        // Pa
  double penalty_asked = 0;  // Pa, α·E or the given p, before limit_penalty lowered it
  // Per contact tetrahedron, the factor (≤ 1) on `penalty` that limit_face_penalty left; a pair
  // takes the smaller of its two. Empty: 1 everywhere.
  std::vector<double> tet_penalty_scale;
  // Per node, the lumped mass scale_contact_mass added (kg, already in `mass`); empty: none.
  std::vector<double> added_mass;
  // The contact factor the world meets: ContactDef::max_contact_factor, or the lower one that
  // scale_contact_mass_within found (0: none).
  double contact_factor = 0;
  double friction = 0;
  ContactLaw law = ContactLaw::potential;
  double kv = 0;  // N/m³
  double kt = 0;  // volume-linear's friction: N/m
  // Volume laws: the surface triangles (columns of face_outward) inside each contact tetrahedron,
  // CSR: tet k owns tet_faces[tet_faces_begin[k] .. tet_faces_begin[k+1]); and the overlaps of the
  // body pairs in contact (kept across steps for volume-linear's work).
  std::vector<int> tet_faces_begin, tet_faces;
  std::vector<BodyOverlap> overlaps;
  // Surface triangles (global nodes) and the penalty stiffness of each pressed into another
  // body, N/m (fdem/time_step.hpp).
  Eigen::Matrix3Xi face_nodes;
  Eigen::Matrix3Xi face_outward;  // the same triangles in the surface's outward order
  std::vector<double> face_stiffness;

  // Broad phase (fdem/broad_phase.hpp): Verlet list of tetrahedron pairs whose boxes, grown by
  // the skin, overlap; rebuilt when a node has moved more than skin/2.
  double skin = 0;  // m
  std::vector<TetPair> pairs;
  Eigen::Matrix3Xd x_at_build;
  long rebuilds = 0;
  // Narrow-phase scratch, per surface tetrahedron: its box, nodes and kernel frame as of contact
  // pass `pass` (the potential law's contact_forces counts its passes in contact_passes), so that
  // a tetrahedron met in several candidate pairs in one step is gathered and inverted once. The
  // boxes sit in an array of their own: every listed pair reads two and most pairs stop there;
  // the nodes and frame (352 bytes) are written only for the tetrahedra of pairs whose boxes
  // overlap (docs/physics.md, "FEM/DEM step cost").
  struct ContactBox {
    Vec3 lo, hi;
    long pass = -1;
  };
  struct ContactTet {
    contact::TetNodes x;
    contact::TetFrame frame;
    long frame_pass = -1;
  };
  std::vector<ContactBox> contact_boxes;
  std::vector<ContactTet> contact_tets;
  long contact_passes = 0;

  // Bookkeeping.
  bool want_energy = true;       // compute elastic and contact energy in the next step
  double elastic_energy = 0;     // J, at the last step that computed it
  double contact_energy = 0;     // J, penalty + friction springs
  double dissipated = 0;         // J, accumulated: viscous damping and friction
  long contact_evaluations = 0;  // candidate pairs run through the kernel, accumulated
  long contacts_touching = 0;    // of those, in contact
  // The largest element rotation of the linear-law bodies so far (fem::InternalForceResult::
  // max_rotation, sin θ); past fem::kLinearMaxRotation the world stops (failure).
  double max_rotation = 0;

  // This step's contact output per body (core/body_contacts.hpp): force, its potential (normal)
  // part, and the deepest overlap among each body's touching pairs.
  BodyContacts contacts;

  // Deepest penetration of the last step relative to the contacting elements: the largest
  // depth / max(height_a, height_b) over the touching pairs (0 when none touches), and the two
  // bodies of that pair. The potential φ at the deepest point is at least this ratio (φ =
  // depth/height in the sub-tetrahedron that holds it, and height ≤ the larger of the two);
  // φ → 1 means a node is reaching an element's centroid, past which the penalty pushes it on
  // through (fdem/runaway_penetration.hpp flags it).
  double penetration = 0;
  int penetration_body_a = -1, penetration_body_b = -1;

  // Set when an element inverted (J ≤ 0), or a linear-law element rotated past
  // fem::kLinearMaxRotation: body, element, value and time; the world stops there.
  std::string failure;

  double time = 0;
  long steps = 0;
  Profile profile;

  int node_count() const { return static_cast<int>(x.cols()); }
};

// Builds the world (throws InputError naming the body for an invalid mesh) and computes the
// initial forces.
World make_world(const WorldDef& def);

// One explicit central-difference step (velocity form): half kick → drift → broad phase →
// contact forces → internal forces → half kick.
void step(World& world, double dt);

// Elastic and contact terms are those of the last step with want_energy set.
EnergyBalance energy(const World& world);

// Linear momentum of all moving bodies, kg·m/s; centre-of-mass velocity of one body, m/s.
Vec3 momentum(const World& world);
Vec3 body_velocity(const World& world, int body);
Vec3 body_centre(const World& world, int body);

}  // namespace asperity::fdem
