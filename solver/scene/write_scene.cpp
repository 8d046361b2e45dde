// A scene written as the contract's JSON (write_scene.hpp).
#include "solver/scene/write_scene.hpp"

#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <variant>

namespace asperity::scene {
namespace {
using OJson = nlohmann::ordered_json;

OJson vec(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

OJson material_json(const Material& m) {
  OJson j = {
      {"density", m.density}, {"young", m.young}, {"poisson", m.poisson}, {"friction", m.friction}};
  if (m.restitution != 1) j["restitution"] = m.restitution;
  if (m.law != ElasticLaw::neo_hookean) j["law"] = elastic_law_name(m.law);
  return j;
}

OJson shape_json(const Shape& shape, const std::filesystem::path& folder) {
  if (const auto* s = std::get_if<SphereShape>(&shape)) {
    return {{"type", "sphere"}, {"radius", s->radius}};
  }
  if (const auto* p = std::get_if<PlaneShape>(&shape)) {
    return {{"type", "plane"}, {"point", vec(p->point)}, {"normal", vec(p->normal)}};
  }
  if (const auto* b = std::get_if<BoxShape>(&shape)) {
    return {{"type", "box"}, {"min", vec(b->min)}, {"max", vec(b->max)}};
  }
  const MeshShape& m = std::get<MeshShape>(shape);
  OJson j = {{"type", "mesh"}, {"file", m.file.lexically_relative(folder).generic_string()}};
  if (m.faces != 0) j["faces"] = m.faces;
  if (m.scale != 1) j["scale"] = m.scale;
  if (m.element_size != 0) j["element_size"] = m.element_size;
  if (m.element_size_focus) {
    j["element_size_focus"] = vec(*m.element_size_focus);
    j["element_size_focus_radius"] = m.element_size_focus_radius;
    j["element_size_growth"] = m.element_size_growth;
  }
  if (std::isfinite(m.element_size_far)) j["element_size_far"] = m.element_size_far;
  return j;
}

OJson body_json(const SceneDef& s, const BodyDef& b, const std::filesystem::path& folder) {
  OJson j = {{"name", b.name},
             {"material", s.materials[static_cast<std::size_t>(b.material)].name},
             {"shape", shape_json(b.shape, folder)}};
  const bool mesh = std::holds_alternative<MeshShape>(b.shape);
  if (mesh) j["model"] = b.model == Model::fem ? "fem" : "rigid";
  if (!b.position.isZero(0)) j["position"] = vec(b.position);
  if (!b.velocity.isZero(0)) j["velocity"] = vec(b.velocity);
  if (!b.angular_velocity.isZero(0)) j["angular_velocity"] = vec(b.angular_velocity);
  // Boxes and planes are fixed without saying so.
  if (b.fixed && (mesh || std::holds_alternative<SphereShape>(b.shape))) j["fixed"] = true;
  if (b.damping_ratio != 0) j["damping_ratio"] = b.damping_ratio;
  return j;
}

OJson contact_json(const ContactDef& c) {
  OJson j = {{"law", contact_law_name(c.law)}};
  const auto put = [&j](const char* key, const std::optional<double>& v) {
    if (v) j[key] = *v;
  };
  put("kn", c.kn);
  put("kt", c.kt);
  put("penalty", c.penalty);
  put("penalty_alpha", c.penalty_alpha);
  put("max_contact_factor", c.max_contact_factor);
  if (c.contact_factor_by != ContactFactorBy::face_penalty)
    j["contact_factor_by"] = name_in(kContactFactorByNames, c.contact_factor_by);
  put("max_added_mass", c.max_added_mass);
  put("kv", c.kv);
  put("friction", c.friction);
  put("restitution", c.restitution);
  return j;
}

}  // namespace

OJson scene_json(const SceneDef& s, const std::filesystem::path& folder) {
  OJson j = {{"name", s.name},
             {"gravity", vec(s.gravity)},
             {"duration", s.duration},
             {"dt", s.dt ? OJson(*s.dt) : OJson("auto")}};
  if (s.dt_safety) j["dt_safety"] = *s.dt_safety;
  if (s.allow_unsafe_dt) j["allow_unsafe_dt"] = true;
  if (s.unstable_energy_growth != 1.0) j["unstable_energy_growth"] = s.unstable_energy_growth;
  if (s.allow_initial_overlap) j["allow_initial_overlap"] = true;
  OJson materials = OJson::object();
  for (const Material& m : s.materials) materials[m.name] = material_json(m);
  j["materials"] = materials;
  OJson bodies = OJson::array();
  for (const BodyDef& b : s.bodies) bodies.push_back(body_json(s, b, folder));
  j["bodies"] = bodies;
  j["contact"] = contact_json(s.contact);
  OJson record = {{"force_on", s.bodies[static_cast<std::size_t>(s.record.body)].name},
                  {"every", s.record.every}};
  if (s.record.end_after_separation) {
    record["end_after_separation"] = *s.record.end_after_separation;
  }
  j["record"] = record;
  OJson output = OJson::object();
  if (s.output.vtk_every != 0) output["vtk_every"] = s.output.vtk_every;
  if (s.output.vtk_ascii) output["vtk_format"] = "ascii";
  if (!output.empty()) j["output"] = output;
  return j;
}

}  // namespace asperity::scene
