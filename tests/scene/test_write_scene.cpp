// A scene written as JSON (scene::scene_json, what the study writes as each case's scene.json)
// reads back as the same scene: every example and every validation case's scene, written and read
// again, has every field the loader sets equal to the original's, and writes the same JSON again.
#include <filesystem>
#include <fstream>
#include <string>
#include <variant>
#include <vector>

#include <gtest/gtest.h>

#include "solver/io/json_file.hpp"
#include "solver/scene/scene.hpp"
#include "solver/scene/scene_json.hpp"
#include "solver/scene/write_scene.hpp"

using namespace asperity;
using namespace asperity::scene;
namespace fs = std::filesystem;

namespace {

void expect_same_shape(const Shape& a, const Shape& b, const std::string& where) {
  ASSERT_EQ(a.index(), b.index()) << where;
  if (const auto* s = std::get_if<SphereShape>(&a)) {
    EXPECT_EQ(s->radius, std::get<SphereShape>(b).radius) << where;
  } else if (const auto* p = std::get_if<PlaneShape>(&a)) {
    EXPECT_EQ(p->point, std::get<PlaneShape>(b).point) << where;
    EXPECT_EQ(p->normal, std::get<PlaneShape>(b).normal) << where;
  } else if (const auto* x = std::get_if<BoxShape>(&a)) {
    EXPECT_EQ(x->min, std::get<BoxShape>(b).min) << where;
    EXPECT_EQ(x->max, std::get<BoxShape>(b).max) << where;
  } else {
    const MeshShape &m = std::get<MeshShape>(a), &n = std::get<MeshShape>(b);
    EXPECT_TRUE(fs::equivalent(m.file, n.file)) << where << m.file << " " << n.file;
    EXPECT_EQ(m.faces, n.faces) << where;
    EXPECT_EQ(m.scale, n.scale) << where;
    EXPECT_EQ(m.element_size, n.element_size) << where;
    EXPECT_EQ(m.element_size_focus, n.element_size_focus) << where;
    EXPECT_EQ(m.element_size_focus_radius, n.element_size_focus_radius) << where;
    EXPECT_EQ(m.element_size_growth, n.element_size_growth) << where;
    EXPECT_EQ(m.element_size_far, n.element_size_far) << where;
  }
}

// Every field of SceneDef but `file` (where it was read from).
void expect_same(const SceneDef& a, const SceneDef& b, const std::string& where) {
  EXPECT_EQ(a.name, b.name) << where;
  EXPECT_EQ(a.gravity, b.gravity) << where;
  EXPECT_EQ(a.duration, b.duration) << where;
  EXPECT_EQ(a.dt, b.dt) << where;
  EXPECT_EQ(a.dt_safety, b.dt_safety) << where;
  EXPECT_EQ(a.allow_unsafe_dt, b.allow_unsafe_dt) << where;
  EXPECT_EQ(a.unstable_energy_growth, b.unstable_energy_growth) << where;
  EXPECT_EQ(a.allow_initial_overlap, b.allow_initial_overlap) << where;
  ASSERT_EQ(a.materials.size(), b.materials.size()) << where;
  for (std::size_t i = 0; i < a.materials.size(); ++i) {
    const Material &m = a.materials[i], &n = b.materials[i];
    EXPECT_EQ(m.name, n.name) << where;
    EXPECT_EQ(m.density, n.density) << where;
    EXPECT_EQ(m.young, n.young) << where;
    EXPECT_EQ(m.poisson, n.poisson) << where;
    EXPECT_EQ(m.friction, n.friction) << where;
    EXPECT_EQ(m.restitution, n.restitution) << where;
    EXPECT_EQ(m.law, n.law) << where;
  }
  ASSERT_EQ(a.bodies.size(), b.bodies.size()) << where;
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    const BodyDef &p = a.bodies[i], &q = b.bodies[i];
    const std::string body = where + " body " + p.name;
    EXPECT_EQ(p.name, q.name) << body;
    EXPECT_EQ(p.material, q.material) << body;
    expect_same_shape(p.shape, q.shape, body);
    EXPECT_EQ(p.model, q.model) << body;
    EXPECT_EQ(p.position, q.position) << body;
    EXPECT_EQ(p.velocity, q.velocity) << body;
    EXPECT_EQ(p.angular_velocity, q.angular_velocity) << body;
    EXPECT_EQ(p.fixed, q.fixed) << body;
    EXPECT_EQ(p.damping_ratio, q.damping_ratio) << body;
  }
  const ContactDef &c = a.contact, &d = b.contact;
  EXPECT_EQ(c.law, d.law) << where;
  EXPECT_EQ(c.kn, d.kn) << where;
  EXPECT_EQ(c.kt, d.kt) << where;
  EXPECT_EQ(c.penalty, d.penalty) << where;
  EXPECT_EQ(c.penalty_alpha, d.penalty_alpha) << where;
  EXPECT_EQ(c.max_contact_factor, d.max_contact_factor) << where;
  EXPECT_EQ(c.contact_factor_by, d.contact_factor_by) << where;
  EXPECT_EQ(c.max_added_mass, d.max_added_mass) << where;
  EXPECT_EQ(c.kv, d.kv) << where;
  EXPECT_EQ(c.friction, d.friction) << where;
  EXPECT_EQ(c.restitution, d.restitution) << where;
  EXPECT_EQ(a.record.body, b.record.body) << where;
  EXPECT_EQ(a.record.every, b.record.every) << where;
  EXPECT_EQ(a.record.end_after_separation, b.record.end_after_separation) << where;
  EXPECT_EQ(a.output.vtk_every, b.output.vtk_every) << where;
  EXPECT_EQ(a.output.vtk_ascii, b.output.vtk_ascii) << where;
}

// The scenes of the examples (files) and of the validation cases (each case's "scene").
std::vector<SceneDef> every_scene() {
  std::vector<SceneDef> out;
  const fs::path root = ASPERITY_SOURCE_DIR;
  for (const auto& e : fs::directory_iterator(root / "examples")) {
    if (e.path().extension() == ".json") out.push_back(load_scene(e.path()));
  }
  for (const auto& e : fs::recursive_directory_iterator(root / "validation" / "cases")) {
    if (e.path().extension() != ".json") continue;
    out.push_back(parse_scene(io::read_json_file(e.path()).at("scene"), e.path(), "scene"));
  }
  // No committed scene starts pressed (the perf table writes its pressed lattice): one that does.
  SceneDef pressed = load_scene(root / "examples" / "glass-sphere-on-plate.json");
  pressed.allow_initial_overlap = true;
  out.push_back(pressed);
  return out;
}

TEST(WriteScene, EveryExampleAndCaseScene) {
  const fs::path dir = fs::temp_directory_path() / "asperity_write_scene_tests";
  fs::create_directories(dir);
  const std::vector<SceneDef> scenes = every_scene();
  // the 5 examples, the 200 validation cases of this tree and the pressed example: a folder that
  // lost its files fails
  ASSERT_GE(scenes.size(), 206u);
  for (const SceneDef& s : scenes) {
    const fs::path file = dir / "scene.json";
    const nlohmann::ordered_json written = scene_json(s, dir);
    std::ofstream(file) << written.dump(1) << "\n";
    const SceneDef back = load_scene(file);
    expect_same(s, back, s.file.string());
    EXPECT_EQ(written, scene_json(back, dir)) << s.file;
  }
}

}  // namespace
