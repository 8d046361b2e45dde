// The guideline lookup behind `asperity recommend`.
#include "study/recommend.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "solver/core/error.hpp"
#include "solver/geometry/local_curvature.hpp"
#include "solver/geometry/mesh_pipeline.hpp"
#include "solver/io/json_file.hpp"
#include "solver/scene/scene.hpp"

namespace asperity::study {
namespace fs = std::filesystem;
using OJson = nlohmann::ordered_json;

double parse_tolerance(const std::string& text, const std::string& key) {
  std::string t = text;
  double scale = 1;
  if (!t.empty() && t.back() == '%') {
    t.pop_back();
    scale = 0.01;
  }
  std::size_t used = 0;
  double v = std::nan("");
  try {
    v = std::stod(t, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != t.size() || !std::isfinite(v)) {
    throw InputError(key + ": must be a fraction or a percentage such as 5% (got \"" + text +
                     "\")");
  }
  v *= scale;
  if (!(v > 0 && v < 1)) throw InputError(key + ": must lie in (0, 100%) (got \"" + text + "\")");
  return v;
}

namespace {

// The particle: the recorded body when it moves, else the first free body.
int advised_body(const scene::SceneDef& s, const fs::path& scene_file) {
  int body = s.record.body;
  if (body < 0 || s.bodies[body].fixed) {
    const auto it = std::find_if(s.bodies.begin(), s.bodies.end(),
                                 [](const scene::BodyDef& b) { return !b.fixed; });
    if (it == s.bodies.end())
      throw InputError(scene_file.string() + ": bodies: no free body (a particle) to advise on");
    body = static_cast<int>(it - s.bodies.begin());
  }
  return body;
}

struct Particle {
  double diameter = 0;  // volume-equivalent, m
  std::string shape;    // "sphere" or "mesh"
  // Hertz's equivalent radius √(R1 R2) at the lowest vertex (the mesh file's −z; the strike point
  // of a fall onto a floor), m; 0 where flat or concave (geometry/local_curvature.hpp).
  double local_radius = 0;
};

Particle particle_of(const scene::BodyDef& b, int body, const fs::path& scene_file) {
  if (const auto* sp = std::get_if<scene::SphereShape>(&b.shape)) {
    return {.diameter = 2 * sp->radius, .shape = "sphere", .local_radius = sp->radius};
  }
  if (const auto* m = std::get_if<scene::MeshShape>(&b.shape)) {
    geometry::PipelineOptions po;
    po.read.scale = m->scale;
    po.tetrahedralize = false;
    const geometry::PreparedParticle p = geometry::prepare_particle(m->file, po);
    // The same patch as the study's sphere-local model (study_meshes.hpp, local_radii).
    const geometry::LocalCurvature k =
        geometry::lowest_point_curvature(p.surface, 2.5 * geometry::mean_edge_length(p.surface));
    return {.diameter = 2 * p.source_props.equivalent_radius,
            .shape = "mesh",
            .local_radius = k.equivalent_radius()};
  }
  throw InputError(scene_file.string() + ": bodies[" + std::to_string(body) +
                   "]: a free plane or box is no particle");
}

// The guideline row: the largest tolerance of the table not above the one asked for
// (conservative), or nullptr; `applied` its tolerance.
const io::Json* pick_row(const io::Json& g, const std::string& placement, const RecommendOptions& o,
                         double& applied) {
  const io::Json* best = nullptr;
  applied = 0;
  for (const io::Json& r : g["rows"]) {
    if (r.at("placement") != placement || r.at("metric") != o.metric ||
        r.at("statistic") != o.statistic)
      continue;
    const double t = r.at("tolerance").get<double>();
    if (t <= o.tolerance * (1 + 1e-12) && t > applied) {
      applied = t;
      best = &r;
    }
  }
  return best;
}

// The recommended model and resolution: the row's, or the study's reference when no row meets
// the tolerance.
OJson recommendation(const io::Json* best, const io::Json& g, OJson& notes) {
  if (best) {
    if ((*best)["is_reference"].get<bool>()) {
      notes.push_back(
          "only the study's finest fem mesh met this tolerance: a finer mesh may be needed");
    }
    // The reference's own uncertainty (guidelines.json from issue 12 on; null in older ones):
    // the expected error is known no better than this.
    const io::Json u = best->value("reference_uncertainty", io::Json());
    if (best->value("resolvable", io::Json()) == io::Json(false)) {
      notes.push_back(
          "the study's reference is uncertain by more than this tolerance: the "
          "expected error is below what the study can resolve");
    }
    return {{"model", (*best)["model"]},
            {"resolution", (*best)["resolution"]},
            {"element_size_rel", best->value("element_size_rel", io::Json())},
            {"expected_error", (*best)["error"]},
            {"reference_uncertainty", u},
            {"cpu_seconds_median_in_study", (*best)["cpu_seconds_median"]},
            {"is_reference", (*best)["is_reference"]}};
  }
  const io::Json& ref = g["reference"];
  notes.push_back(
      "no guideline at or below this tolerance (it is tighter than 2%, or nothing the study "
      "measured met it, its finest refined fem included): the study's finest fem, and a "
      "convergence check of your own");
  return {{"model", ref["model"]},
          {"resolution", ref["resolution"]},
          {"element_size_rel", ref.value("element_size_rel", io::Json())},
          {"expected_error", nullptr},
          {"reference_uncertainty", nullptr},
          {"cpu_seconds_median_in_study", nullptr},
          {"is_reference", true}};
}

// The scene keys to change for the recommended model.
OJson scene_change(const OJson& rec, const io::Json& g, const Particle& particle) {
  const double diameter = particle.diameter;
  const std::string model = rec["model"].get<std::string>();
  if (model == "sphere") {
    return {{"shape", {{"type", "sphere"}, {"radius", diameter / 2}}}, {"contact.law", "hertz"}};
  }
  if (model == "sphere-local") {
    // Hertz at the local radius, carrying the particle's mass: its density times the volume
    // ratio (the equivalent sphere's volume over the local sphere's).
    const double r = particle.local_radius;
    return {{"shape", {{"type", "sphere"}, {"radius", r > 0 ? OJson(r) : OJson()}}},
            {"material.density_factor", r > 0 ? OJson(std::pow(diameter / (2 * r), 3)) : OJson()},
            {"contact.law", "hertz"}};
  }
  // "rigid" is the rigid polyhedron under the elastic volume law; "rigid-penalty" under the
  // potential (the study's comparison model).
  OJson change = {{"model", model == "fem" ? "fem" : "rigid"},
                  {"shape.faces", rec["resolution"]},
                  {"contact.law", model == "rigid" ? "volume-hertz" : "potential"}};
  // The guideline holds for the study's penalty (its peak forces depend on it, docs/study.md).
  const io::Json alpha = g.value("penalty_alpha", io::Json());
  if (alpha.is_number() && model != "rigid") change["contact.penalty_alpha"] = alpha.get<double>();
  // A refined fem answer: the element size at the strike point (the particle's lowest point
  // for a fall onto a floor), graded as the study graded it.
  const io::Json h = rec.value("element_size_rel", io::Json());
  if (model == "fem" && h.is_number()) {
    change["shape.element_size"] = h.get<double>() * diameter / 2;
    const io::Json grading = g.value("refinement", io::Json());
    if (grading.is_object()) {
      change["shape.element_size_focus_radius"] =
          grading.value("focus_radius", 4.0) * h.get<double>() * diameter / 2;
      change["shape.element_size_growth"] = grading.value("growth", 0.3);
      const double factor = grading.value("max_contact_factor", 0.0);
      if (factor > 0) change["contact.max_contact_factor"] = factor;
    }
  }
  return change;
}

}  // namespace

OJson recommend(const fs::path& scene_file, const fs::path& guidelines_file,
                const RecommendOptions& o) {
  const scene::SceneDef s = scene::load_scene(scene_file);
  const int body = advised_body(s, scene_file);
  const scene::BodyDef& b = s.bodies[body];
  const Particle particle = particle_of(b, body, scene_file);
  const double diameter = particle.diameter;
  const double speed = b.velocity.norm();

  const io::Json g = io::read_json_file(guidelines_file);
  const io::JsonReader gr(g, guidelines_file, "");
  const io::JsonReader rows = gr.child("rows");
  const std::size_t n = rows.require_array();
  if (n == 0)
    throw InputError(guidelines_file.string() + ": rows: empty (the study has no fem reference)");
  const std::string placement = o.placement.empty() ? rows.at(0).string("placement") : o.placement;
  double applied = 0;
  const io::Json* best = pick_row(g, placement, o, applied);
  OJson notes = OJson::array();
  const OJson rec = recommendation(best, g, notes);
  const std::string model = rec["model"].get<std::string>();
  const OJson change = scene_change(rec, g, particle);
  const io::Json range = g.value("particle_diameter_range", io::Json());
  const double study_speed = g.value("speed", 0.0);
  bool in_size = true, in_speed = true;
  if (range.is_array() && range.size() == 2) {
    in_size = diameter >= range[0].get<double>() / 1.5 && diameter <= range[1].get<double>() * 1.5;
    if (!in_size)
      notes.push_back(
          "the particle's size lies outside the study's range (x1.5): the guideline is "
          "extrapolated");
  }
  if (study_speed > 0) {
    in_speed = speed >= study_speed / 2 && speed <= study_speed * 2;
    if (!in_speed)
      notes.push_back(
          "the impact speed lies outside half to twice the study's: the guideline is extrapolated");
  }
  if (model == "fem" && rec["element_size_rel"].is_number()) {
    notes.push_back(
        "set shape.element_size_focus to the strike point (the mesh file's "
        "coordinates; the lowest point for a fall onto a floor)");
  }
  if (model == "sphere-local" && !(particle.local_radius > 0)) {
    notes.push_back(
        "the particle is flat or concave at its lowest vertex: no local sphere; take the next "
        "guideline");
  }
  if (particle.shape == "sphere" && model != "sphere" && model != "sphere-local") {
    notes.push_back(
        "the scene's particle is a sphere: the guideline is for irregular particles; mesh the real "
        "shape");
  }
  return {{"scene", scene_file.string()},
          {"guidelines", guidelines_file.string()},
          {"particle",
           {{"body", b.name},
            {"shape", particle.shape},
            {"equivalent_diameter", diameter},
            {"speed", speed}}},
          {"tolerance", o.tolerance},
          {"applied_tolerance", best ? OJson(applied) : OJson()},
          {"metric", o.metric},
          {"statistic", o.statistic},
          {"placement", placement},
          {"recommendation", rec},
          {"scene_change", change},
          {"within_study_range", {{"size", in_size}, {"speed", in_speed}}},
          {"notes", notes}};
}

}  // namespace asperity::study
