// Scene loading: every key validated once, here, at the edge (docs/contract.md, "Scene file").
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "solver/core/error.hpp"
#include "solver/io/json_file.hpp"
#include "solver/scene/scene.hpp"
#include "solver/scene/scene_json.hpp"
#include "solver/scene/scene_keys.hpp"

namespace asperity::scene {
namespace {

using io::JsonReader;

constexpr double kSpeedOfLight = 299'792'458.0;  // m/s

Material parse_material(const JsonReader& m, const std::string& name) {
  m.only_keys_in(keys::kMaterial);
  Material out;
  out.name = name;
  out.density = m.positive("density");
  out.young = m.positive("young");
  // Thermodynamic bounds of an isotropic solid: −1 < ν < 1/2.
  out.poisson = m.in_range("poisson", -1.0, 0.5, true, true);
  out.friction = m.has("friction") ? m.in_range("friction", 0.0, 1e3, false, false) : 0.0;
  out.restitution =
      m.has("restitution") ? m.in_range("restitution", kMinRestitution, 1.0, false, false) : 1.0;
  if (m.has("law")) {
    const std::string law = m.string("law");
    if (const std::optional<ElasticLaw> known = elastic_law_from_name(law)) {
      out.law = *known;
    } else {
      const std::string near = io::closest_key(law, names_in(kElasticLawNames));
      m.fail("law", "unknown elastic law " + io::echo(m.value().at("law")) +
                        (near.empty() ? "" : " (did you mean \"" + near + "\"?)") +
                        "; expected neo-hookean or linear");
    }
  }
  return out;
}

Shape parse_shape(const JsonReader& s) {
  s.require_object();
  const std::string type = s.string("type");
  if (type == "sphere") {
    s.only_keys_in(keys::kSphere);
    return SphereShape{.radius = s.positive("radius")};
  }
  if (type == "plane") {
    s.only_keys_in(keys::kPlane);
    PlaneShape p{.point = s.vec3("point"), .normal = s.vec3("normal")};
    // Scaled by its largest component first: the norm of [1e308, 1e308, 0] overflows, and the
    // normal became zero (a plane that overlapped everything).
    const double largest = p.normal.cwiseAbs().maxCoeff();
    if (!(largest > 0) || (p.normal / largest).norm() * largest < 1e-12)
      s.fail("normal", "must be a non-zero vector (got " + io::echo(s.value().at("normal")) + ")");
    p.normal = (p.normal / largest).normalized();
    return p;
  }
  if (type == "box") {
    s.only_keys_in(keys::kBox);
    BoxShape b{.min = s.vec3("min"), .max = s.vec3("max")};
    if (!(b.max.array() > b.min.array()).all()) s.fail("max", "must exceed min in every axis");
    return b;
  }
  if (type == "mesh") {
    s.only_keys_in(keys::kMesh);
    MeshShape m;
    m.file = s.string("file");
    // "" joined to the scene's folder names the folder, and the message named it instead.
    if (m.file.empty()) s.fail("file", "must name a mesh file (got \"\")");
    if (m.file.is_relative()) m.file = s.file().parent_path() / m.file;
    m.faces = s.has("faces") ? static_cast<int>(s.integer("faces", 4, 10'000'000)) : 0;
    m.scale = s.has("scale") ? s.positive("scale") : 1.0;
    // Positive here; against the particle's size and the tetrahedra it would make, where the
    // mesh is read (geometry::element_size_problem).
    m.element_size = s.has("element_size") ? s.positive("element_size") : 0.0;
    for (const char* k : {"element_size_focus", "element_size_focus_radius", "element_size_growth",
                          "element_size_far"}) {
      if (s.has(k) && !s.has("element_size")) s.fail(k, "needs element_size (the size it grades)");
    }
    if (s.has("element_size_focus")) m.element_size_focus = s.vec3("element_size_focus");
    m.element_size_focus_radius =
        s.has("element_size_focus_radius")
            ? s.in_range("element_size_focus_radius", 0, 1e3, false, false)
            : 0.0;
    m.element_size_growth =
        s.has("element_size_growth") ? s.in_range("element_size_growth", 0, 10, false, false) : 0.0;
    if (s.has("element_size_far")) {
      m.element_size_far = s.positive("element_size_far");
      if (m.element_size_far < m.element_size)
        s.fail("element_size_far", "must be at least element_size");
    }
    return m;
  }
  const std::string near = io::closest_key(type, {"sphere", "plane", "box", "mesh"});
  s.fail("type", "unknown shape \"" + type + "\"" +
                     (near.empty() ? "" : " (did you mean \"" + near + "\"?)") +
                     "; expected sphere, plane, box or mesh");
}

ContactDef parse_contact(const JsonReader& c) {
  c.only_keys_in(keys::kContact);
  ContactDef out;
  const std::string law = c.string("law");
  const std::vector<std::string_view> names = names_in(kContactLawNames);
  if (const std::optional<ContactLaw> known = contact_law_from_name(law)) {
    out.law = *known;
    if (out.law == ContactLaw::linear) out.kn = c.positive("kn");
    if (out.law == ContactLaw::volume_linear) {
      if (!c.has("kv"))
        c.fail("kv", "volume-linear needs kv, the volumetric stiffness in N/m³ (F_n = kv · V)");
      out.kv = c.positive("kv");
    }
  } else {
    const std::string near = io::closest_key(law, names);
    std::string expected;
    for (std::size_t i = 0; i < names.size(); ++i) {
      expected += (i == 0 ? "" : (i + 1 == names.size() ? " or " : ", ")) + std::string(names[i]);
    }
    c.fail("law", "unknown contact law \"" + law + "\"" +
                      (near.empty() ? "" : " (did you mean \"" + near + "\"?)") + "; expected " +
                      expected);
  }
  if (c.has("kv") && !out.kv) c.fail("kv", "only the volume-linear law takes kv");
  if (c.has("kn") && !out.kn) c.fail("kn", "only the linear law takes kn");
  if (c.has("kt")) {
    if (out.law == ContactLaw::volume_hertz) {
      c.fail("kt",
             "volume-hertz takes Mindlin's tangential stiffness 8 G* a from the overlap; "
             "only the linear and volume-linear laws take kt");
    }
    if (out.law != ContactLaw::linear && out.law != ContactLaw::volume_linear)
      c.fail("kt", "only the linear and volume-linear laws take kt");
    out.kt = c.positive("kt");
  }
  if (c.has("penalty")) {
    if (out.law != ContactLaw::potential) c.fail("penalty", "only the potential law takes penalty");
    out.penalty = c.positive("penalty");
  }
  if (c.has("penalty_alpha")) {
    if (out.law != ContactLaw::potential) {
      c.fail("penalty_alpha", "only the potential law takes penalty_alpha");
    }
    if (out.penalty) c.fail("penalty_alpha", "give penalty (Pa) or penalty_alpha, not both");
    // α = p/E (docs/physics.md, "Penalty"); the study definition's range, from kMinPenaltyAlpha.
    out.penalty_alpha = c.in_range("penalty_alpha", kMinPenaltyAlpha, 1e6, false, false);
  }
  if (c.has("max_contact_factor")) {
    if (out.law != ContactLaw::potential) {
      c.fail("max_contact_factor", "only the potential law takes max_contact_factor");
    }
    // 0: the penalty as asked wherever it sets the step; below 1 no step could meet it.
    const double f = c.in_range("max_contact_factor", 0, 1e6, false, false);
    if (f > 0 && f < 1) {
      c.fail("max_contact_factor",
             "must be 0 (no limit) or at least 1 (the contact cannot lengthen the elements' step)");
    }
    out.max_contact_factor = f;
  }
  if (c.has("contact_factor_by")) {
    if (out.law != ContactLaw::potential) {
      c.fail("contact_factor_by", "only the potential law takes contact_factor_by");
    }
    const std::string by = c.string("contact_factor_by");
    if (const std::optional<ContactFactorBy> known = value_named(kContactFactorByNames, by)) {
      out.contact_factor_by = *known;
    } else {
      c.fail("contact_factor_by", "unknown \"" + by + "\"; expected face-penalty, penalty or mass");
    }
  }
  if (c.has("max_added_mass")) {
    if (out.contact_factor_by != ContactFactorBy::mass) {
      c.fail("max_added_mass", "only contact_factor_by \"mass\" takes max_added_mass");
    }
    // No factor (0, or a penalty given without one: run/run_fdem.cpp) leaves nothing to lower.
    if (out.max_contact_factor ? *out.max_contact_factor == 0 : out.penalty || out.penalty_alpha) {
      c.fail("max_added_mass", "needs a max_contact_factor above 0 (the factor it lowers)");
    }
    // A fraction of the body's mass: above 0, and below 1 (a body twice its mass is no budget).
    out.max_added_mass = c.in_range("max_added_mass", 0.0, 1.0, true, true);
  }
  if (c.has("friction")) out.friction = c.in_range("friction", 0.0, 1e3, false, false);
  if (c.has("restitution"))
    out.restitution = c.in_range("restitution", kMinRestitution, 1.0, false, false);
  return out;
}

// The step keys: dt (a number or "auto"), dt_safety, allow_unsafe_dt, unstable_energy_growth.
void parse_step(const JsonReader& r, SceneDef& s) {
  if (r.has("dt")) {
    const auto& dt = r.value().at("dt");
    if (dt.is_string()) {
      if (dt.get<std::string>() != "auto")
        r.fail("dt", "must be a number or \"auto\" (got " + io::echo(dt) + ")");
    } else {
      s.dt = r.positive("dt");
    }
  }
  // A safety factor above 1 is past the predicted limit by construction.
  if (r.has("dt_safety")) s.dt_safety = r.in_range("dt_safety", 0.0, 1.0, true, false);
  s.allow_unsafe_dt = r.boolean_or("allow_unsafe_dt", false);
  if (r.has("unstable_energy_growth"))
    s.unstable_energy_growth = r.positive("unstable_energy_growth");
}

// The materials, by name; `law_given` lists those that name an elastic law (checked once the
// bodies are known: check_elastic_laws).
std::map<std::string, int> parse_materials(const JsonReader& mats,
                                           const std::filesystem::path& file, SceneDef& s,
                                           std::vector<std::string>& law_given) {
  mats.require_object();
  if (mats.value().empty()) mats.fail("", "must define at least one material");
  if (mats.value().size() > kMaxMaterials) {
    mats.fail("", std::to_string(mats.value().size()) + " materials, more than the " +
                      std::to_string(kMaxMaterials) +
                      " a scene may define (every pair of them is set up before the run)");
  }
  std::map<std::string, int> material_index;
  for (const auto& [name, m] : mats.value().items()) {
    material_index[name] = static_cast<int>(s.materials.size());
    const JsonReader mr(m, file, mats.path() + "." + name);
    s.materials.push_back(parse_material(mr, name));
    if (mr.has("law")) law_given.push_back(name);
  }
  return material_index;
}

// One body (its keys checked, its name already read and checked unique).
BodyDef parse_body(const JsonReader& b, BodyDef body,
                   const std::map<std::string, int>& material_index) {
  const std::string mat = b.string("material");
  auto it = material_index.find(mat);
  if (it == material_index.end()) b.fail("material", "no material named \"" + mat + "\"");
  body.material = it->second;
  body.shape = parse_shape(b.child("shape"));
  if (b.has("model")) {
    const std::string model = b.string("model");
    if (model == "rigid") {
      body.model = Model::rigid;
    } else if (model == "fem") {
      body.model = Model::fem;
    } else {
      b.fail("model", "must be \"rigid\" or \"fem\" (got \"" + model + "\")");
    }
  }
  body.position = b.vec3_or("position", Vec3::Zero());
  body.velocity = b.vec3_or("velocity", Vec3::Zero());
  // Newtonian contact mechanics ends well below the speed of light; beyond it the step bounds
  // (which scale with 1/v) underflow to 0 and the message would be "inf steps of 0 s".
  // (The norm of [0, 0, 1e308] overflows to inf, which still compares above.)
  if (body.velocity.norm() > kSpeedOfLight) {
    b.fail("velocity", "faster than light (got " + io::echo(b.value().at("velocity")) +
                           " m/s; the speed of light is 299792458 m/s)");
  }
  body.angular_velocity = b.vec3_or("angular_velocity", Vec3::Zero());
  const bool is_wall = std::holds_alternative<PlaneShape>(body.shape) ||
                       std::holds_alternative<BoxShape>(body.shape);
  body.fixed = b.boolean_or("fixed", is_wall);
  if (is_wall && !body.fixed)
    b.fail("fixed", "planes and boxes are fixed bodies; use a mesh body for a moving block");
  if (is_wall && body.model == Model::fem)
    b.fail("model", "planes and boxes are rigid; use a mesh body for a deformable block");
  if (std::holds_alternative<SphereShape>(body.shape) && body.model == Model::fem) {
    b.fail("model", "a sphere is rigid here; mesh it (shape \"mesh\") to make it deformable");
  }
  if (b.has("damping_ratio")) {
    if (body.model != Model::fem || body.fixed)
      b.fail("damping_ratio", "only a moving deformable body (model \"fem\") takes damping");
    body.damping_ratio = b.in_range("damping_ratio", 0.0, 100.0, false, false);
  }
  return body;
}

// An elastic law acts on a deformable body's tetrahedra only: a law on a material that no fem
// body uses would be silently ignored, so it is refused like any other key that does nothing.
void check_elastic_laws(const JsonReader& mats, const SceneDef& s,
                        const std::map<std::string, int>& material_index,
                        const std::vector<std::string>& law_given) {
  for (const std::string& name : law_given) {
    const int index = material_index.at(name);
    bool used = false;
    for (const BodyDef& body : s.bodies) used |= body.material == index && body.model == Model::fem;
    if (!used) {
      mats.child(name).fail("law",
                            "only deformable bodies (model \"fem\") take an elastic law, "
                            "and no fem body uses material \"" +
                                name + "\"");
    }
  }
}

// The potential law acts between tetrahedral meshes; a sphere has none (say so here, where the
// key is known, rather than as a shape problem in the runner).
void check_potential_bodies(const JsonReader& r, const SceneDef& s) {
  if (s.contact.law == ContactLaw::potential) {
    for (std::size_t i = 0; i < s.bodies.size(); ++i) {
      if (std::holds_alternative<SphereShape>(s.bodies[i].shape)) {
        r.child("contact").fail(
            "law", "\"potential\" acts between meshed bodies, and bodies[" + std::to_string(i) +
                       "] is a sphere; use hertz, hertz-mindlin or linear, or mesh the sphere "
                       "(shape \"mesh\")");
      }
    }
  }
}

// A penalty in Pa is held to the α range as well: p/E of the largest Young's modulus of the
// moving bodies (of all, when none moves), as fdem::contact_penalty takes it.
void check_penalty_range(const JsonReader& r, const SceneDef& s) {
  if (s.contact.penalty) {
    double young = 0;
    for (const BodyDef& b : s.bodies)
      if (!b.fixed) young = std::max(young, s.materials[b.material].young);
    if (young == 0)
      for (const BodyDef& b : s.bodies) young = std::max(young, s.materials[b.material].young);
    const double alpha = *s.contact.penalty / young;
    if (!(alpha >= kMinPenaltyAlpha && alpha <= 1e6)) {
      std::ostringstream m;
      m << *s.contact.penalty << " Pa is " << alpha
        << " times the largest moving body's Young's modulus (" << young << " Pa); it must be "
        << kMinPenaltyAlpha << " to 1e+06 times it";
      r.child("contact").fail("penalty", m.str());
    }
  }
}

// The output block (docs/scenes.md): ParaView frames.
OutputDef parse_output(const JsonReader& out) {
  OutputDef o;
  out.only_keys_in(keys::kOutput);
  if (out.has("vtk_every")) {
    o.vtk_every = static_cast<int>(out.integer("vtk_every", 1, 1'000'000'000));
  }
  if (out.has("vtk_format")) {
    const std::string f = out.string("vtk_format");
    if (f != "base64" && f != "ascii") {
      out.fail("vtk_format", "must be \"base64\" or \"ascii\" (got \"" + f + "\")");
    }
    o.vtk_ascii = f == "ascii";
  }
  return o;
}

// The record block, or by default the first free body (else the first), every step.
RecordDef parse_record(const JsonReader& r, const SceneDef& s) {
  RecordDef rd;
  if (r.has("record")) {
    const JsonReader rec = r.child("record");
    rec.only_keys_in(keys::kRecord);
    const std::string who = rec.string("force_on");
    rd.body = -1;
    for (std::size_t i = 0; i < s.bodies.size(); ++i) {
      if (s.bodies[i].name == who) rd.body = static_cast<int>(i);
    }
    if (rd.body < 0) rec.fail("force_on", "no body named \"" + who + "\"");
    if (rec.has("every")) rd.every = static_cast<int>(rec.integer("every", 1, 1'000'000'000));
    if (rec.has("end_after_separation")) {
      rd.end_after_separation = rec.positive("end_after_separation");
    }
  } else {
    for (std::size_t i = 0; i < s.bodies.size() && rd.body < 0; ++i) {
      if (!s.bodies[i].fixed) rd.body = static_cast<int>(i);
    }
    if (rd.body < 0) rd.body = 0;
  }
  return rd;
}

}  // namespace

SceneDef parse_scene(const io::Json& json, const std::filesystem::path& file,
                     const std::string& prefix) {
  const JsonReader r(json, file, prefix);
  // A validation case holds a scene; "unknown key case" would hide what the user has in hand.
  if (prefix.empty() && r.has("case") && r.has("scene")) {
    r.fail("",
           "this is a validation case (it has \"case\" and \"scene\"), not a scene; run it "
           "with asperity validate");
  }
  r.only_keys_in(keys::kScene);
  SceneDef s;
  s.file = file;
  s.name = r.has("name") ? r.string("name") : file.stem().string();
  s.gravity = r.vec3_or("gravity", Vec3::Zero());
  s.duration = r.positive("duration");
  parse_step(r, s);
  s.allow_initial_overlap = r.boolean_or("allow_initial_overlap", false);
  const JsonReader mats = r.child("materials");
  std::vector<std::string> law_given;
  const std::map<std::string, int> material_index = parse_materials(mats, file, s, law_given);
  const JsonReader bodies = r.child("bodies");
  const std::size_t n = bodies.require_array();
  if (n == 0) bodies.fail("", "must list at least one body");
  std::set<std::string> names;
  for (std::size_t i = 0; i < n; ++i) {
    const JsonReader b = bodies.at(i);
    b.only_keys_in(keys::kBody);
    BodyDef body;
    body.name = b.string("name");
    if (!names.insert(body.name).second)
      b.fail("name", "duplicate body name \"" + body.name + "\"");
    s.bodies.push_back(parse_body(b, std::move(body), material_index));
  }
  check_elastic_laws(mats, s, material_index, law_given);

  // A starting overlap is allowed to spheres alone: mesh bodies keep their check
  // (run/run_fdem.cpp), where the penalty contact has no pressed state to start from. A key that
  // does nothing is refused.
  if (s.allow_initial_overlap) {
    for (std::size_t i = 0; i < s.bodies.size(); ++i) {
      if (std::holds_alternative<MeshShape>(s.bodies[i].shape)) {
        r.fail("allow_initial_overlap",
               "sphere scenes only (spheres, planes and boxes), and bodies[" + std::to_string(i) +
                   "] \"" + s.bodies[i].name + "\" is a mesh");
      }
    }
  }

  if (r.has("contact")) s.contact = parse_contact(r.child("contact"));
  check_potential_bodies(r, s);
  check_penalty_range(r, s);
  if (r.has("output")) s.output = parse_output(r.child("output"));
  s.record = parse_record(r, s);
  return s;
}

SceneDef load_scene(const std::filesystem::path& file) {
  return parse_scene(io::read_json_file(file), file, "");
}

}  // namespace asperity::scene
