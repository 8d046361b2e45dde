// A scene as the contract defines it (docs/contract.md): plain definition structs, SI units.
#pragma once

#include <array>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "solver/core/material.hpp"
#include "solver/core/vec.hpp"

namespace asperity::scene {

struct SphereShape {
  double radius = 0;  // m
};
struct PlaneShape {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();  // unit, pointing into the free half-space
};
struct BoxShape {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();
};
struct MeshShape {
  std::filesystem::path file;  // resolved against the scene file's folder
  int faces = 0;               // 0: keep the file's triangles
  double scale = 1;            // multiplies the file's coordinates (e.g. 1e-3 for mm)
  // m, after scale; 0: the surface triangles are the elements' faces. Otherwise the target
  // tetrahedron edge length, the surface bisected in its own planes to meet it (the geometry
  // unchanged) and the interior filled with quality tetrahedra (docs/geometry.md).
  double element_size = 0;
  // Grading of element_size towards a point (geometry::ElementSize): the size holds within
  // `element_size_focus_radius` of `element_size_focus` (m, the mesh file's coordinates after
  // scale, before the body is placed) and grows beyond it at `element_size_growth` m per m up to
  // `element_size_far`. No focus: uniform. The study grades towards each particle's strike point.
  std::optional<Vec3> element_size_focus;
  double element_size_focus_radius = 0;
  double element_size_growth = 0;
  double element_size_far = std::numeric_limits<double>::infinity();
};
using Shape = std::variant<SphereShape, PlaneShape, BoxShape, MeshShape>;

enum class Model { rigid, fem };

struct BodyDef {
  std::string name;
  int material = -1;  // index into SceneDef::materials
  Shape shape;
  Model model = Model::rigid;
  Vec3 position = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();
  Vec3 angular_velocity = Vec3::Zero();
  bool fixed = false;
  // Model "fem" only: damping ratio ξ of the body's highest element mode, from stiffness-
  // proportional Kelvin–Voigt damping (lower modes get ξ ω/ω_max; fdem::BodyDef::damping_ratio).
  double damping_ratio = 0;
};

enum class ContactLaw { hertz, hertz_mindlin, linear, potential, volume_hertz, volume_linear };

// The scene's name of each law: the one table the loader parses with and summaries write.
inline constexpr NameTable<ContactLaw, 6> kContactLawNames{{
    {ContactLaw::hertz, "hertz"},
    {ContactLaw::hertz_mindlin, "hertz-mindlin"},
    {ContactLaw::linear, "linear"},
    {ContactLaw::potential, "potential"},
    {ContactLaw::volume_hertz, "volume-hertz"},
    {ContactLaw::volume_linear, "volume-linear"},
}};
inline std::string contact_law_name(ContactLaw law) {
  return name_in(kContactLawNames, law);
}
inline std::optional<ContactLaw> contact_law_from_name(std::string_view name) {
  return value_named(kContactLawNames, name);
}

// What meets contact.max_contact_factor (fdem::ContactStepFix): the penalty of the faces that
// set the step, the one penalty of every face, or the mass of the surface nodes that set it.
enum class ContactFactorBy { face_penalty, penalty, mass };
inline constexpr NameTable<ContactFactorBy, 3> kContactFactorByNames{{
    {ContactFactorBy::face_penalty, "face-penalty"},
    {ContactFactorBy::penalty, "penalty"},
    {ContactFactorBy::mass, "mass"},
}};

struct ContactDef {
  ContactLaw law = ContactLaw::hertz_mindlin;
  std::optional<double> kn;             // linear: normal stiffness, N/m
  std::optional<double> kt;             // linear: tangential stiffness, N/m (default 2/7 kn)
  std::optional<double> penalty;        // potential: penalty p, Pa (default α·E)
  std::optional<double> penalty_alpha;  // potential: α in p = α·E (E the largest moving body's
                                        // Young's modulus; default 10); exclusive with penalty
  // potential: how far the penalty contact may pull a deformable body's predicted step below its
  // elements' own limit (≥ 1; 0: no limit), and what gives way where it would pull further
  // (fdem::ContactStepFix; docs/physics.md, "Time step").
  std::optional<double> max_contact_factor;
  ContactFactorBy contact_factor_by = ContactFactorBy::face_penalty;
  // potential, contact_factor_by mass: the factor lowered from max_contact_factor towards 1 as far
  // as the mass added stays within this fraction of the body's (fdem::scale_contact_mass_within).
  std::optional<double> max_added_mass;
  std::optional<double> kv;           // volume-linear: volumetric stiffness, N/m³
  std::optional<double> friction;     // overrides the materials' pair friction
  std::optional<double> restitution;  // overrides the materials' pair restitution
};

struct RecordDef {
  int body = -1;  // index into SceneDef::bodies
  int every = 1;  // steps between rows of force.csv and energy.csv
  // s; when set, the run ends once the recorded body's contact has ended and no new one has
  // begun for this long (an impact study needs the pulse, not the rebound flight after it).
  std::optional<double> end_after_separation;
};

// What `asperity run` writes beside the contract's files.
struct OutputDef {
  int vtk_every = 0;       // steps between ParaView frames (DIR/vtk/); 0: none
  bool vtk_ascii = false;  // ASCII arrays instead of appended base64
};

// Limits a scene is held to (docs/hostile.md):
// - Materials: the sphere contact keeps a constant table of every material pair (n², with a
//   damping solve per distinct restitution): 2,000 materials did not finish setting up in 60 s and
//   20,000 ended in std::bad_alloc. A scene of this suite names a dozen.
inline constexpr std::size_t kMaxMaterials = 64;
// - Restitution: the damping that realises e is found by integrating the clipped contact to
//   separation (contact/restitution_damping.hpp), which takes about 1/e² steps of its clock: at
//   1e-3 a few tenths of a second; below 1e-10 it never separated. 1e-3 is a dead stop already.
inline constexpr double kMinRestitution = 1e-3;
// - Penalty of the potential law (contact.penalty_alpha, and contact.penalty over the largest
//   moving body's Young's modulus): at least this. A softer penalty lets a body sink through
//   another faster than the runaway-penetration checks can see at the step it sets (the penalty
//   sets a rigid body's step alone): `penalty: 1e-300` ran to status ok with the bodies passing
//   through each other. The study runs α = 10 to 1000; tests/fdem/scenes/soft-penalty-tunnel.json
//   (α = 2e-5) is still caught as runaway penetration (exit 3).
inline constexpr double kMinPenaltyAlpha = 1e-6;

struct SceneDef {
  std::filesystem::path file;  // where it was read from (for messages)
  std::string name;
  Vec3 gravity = Vec3::Zero();
  double duration = 0;
  std::optional<double> dt;  // empty: "auto"
  // Factor on the predicted critical step for "auto"; empty: the model's own default (spheres
  // 0.01; FEM/DEM 0.5, rigid-only 0.1: run/step_policy.hpp). Runs report the one used as
  // summary "dt_safety".
  std::optional<double> dt_safety;
  bool allow_unsafe_dt = false;  // run a given dt above the predicted critical step
  // Energy growth, as a fraction of the energy the physics supplied, that stops a run as
  // unstable. An unstable leapfrog grows geometrically past any bound within a few steps; a
  // stable one near ω dt = 2 has a bounded error (1 − (ω dt/2)²)⁻¹ − 1 that passes 100 % from
  // ω dt ≈ 1.41: such a run is flagged too, as its energies are meaningless.
  double unstable_energy_growth = 1.0;
  // Sphere scenes only: bodies may start overlapping (a pressed packing, loaded from its first
  // step by the contact law at the starting overlap). Off, a starting overlap is refused: it is
  // usually a mistake, and the first step fires the bodies apart with the stored elastic energy.
  bool allow_initial_overlap = false;
  std::vector<Material> materials;
  std::vector<BodyDef> bodies;
  ContactDef contact;
  RecordDef record;
  OutputDef output;
};

// Reads and validates a scene file. Throws InputError naming file, key and problem.
SceneDef load_scene(const std::filesystem::path& file);

}  // namespace asperity::scene
