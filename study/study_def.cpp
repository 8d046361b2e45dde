// STUDY.json → StudyDef, validated once at the edge (docs/study.md lists every key).
#include "study/study_def.hpp"

#include <algorithm>

#include "solver/core/error.hpp"
#include "solver/io/json_file.hpp"
#include "solver/io/plain_name.hpp"
#include "solver/scene/scene.hpp"

namespace asperity::study {
namespace fs = std::filesystem;
using io::Json;
using io::JsonReader;

const char* placement_name(Placement p) {
  return p == Placement::centroid ? "centroid" : "lowest";
}

const char* model_name(ModelKind m) {
  switch (m) {
    case ModelKind::fem:
      return "fem";
    case ModelKind::rigid:
      return "rigid";
    case ModelKind::rigid_penalty:
      return "rigid-penalty";
    case ModelKind::sphere:
      return "sphere";
    case ModelKind::sphere_local:
      return "sphere-local";
  }
  return "?";
}

std::optional<ModelKind> model_of(std::string_view name) {
  for (ModelKind m : {ModelKind::fem, ModelKind::rigid, ModelKind::rigid_penalty, ModelKind::sphere,
                      ModelKind::sphere_local}) {
    if (name == model_name(m)) return m;
  }
  return std::nullopt;
}

const char* reference_name(ReferenceKind r) {
  return r == ReferenceKind::source ? "source" : "finest";
}

bool Refinement::applies(long resolution, Placement p) const {
  return !sizes.empty() &&
         (resolutions.empty() ||
          std::find(resolutions.begin(), resolutions.end(), resolution) != resolutions.end()) &&
         (placements.empty() ||
          std::find(placements.begin(), placements.end(), p) != placements.end());
}

namespace {

Material read_material(const JsonReader& m, const std::string& name, const Material& fallback) {
  m.require_object();
  m.only_keys({"density", "young", "poisson", "friction"});
  Material out = fallback;
  out.name = name;
  if (m.has("density")) out.density = m.positive("density");
  if (m.has("young")) out.young = m.positive("young");
  if (m.has("poisson")) out.poisson = m.in_range("poisson", -1, 0.5, true, true);
  if (m.has("friction")) out.friction = m.in_range("friction", 0, 10, false, false);
  return out;
}

// "set": a particle set file (data/particles/set.json) with optional "count" (the first N,
// or "all") and "names" (only these).
void read_set(const JsonReader& p, const fs::path& base, std::vector<ParticleSource>& out) {
  const fs::path set_file = base / p.string("set");
  const Json set_json = io::read_json_file(set_file);
  const JsonReader root(set_json, set_file, "");
  const JsonReader list = root.child("particles");
  const std::size_t n = list.require_array();
  std::size_t count = n;
  if (p.has("count") && !(p.value()["count"].is_string() && p.value()["count"] == "all")) {
    count = static_cast<std::size_t>(p.integer("count", 1, static_cast<long long>(n)));
  }
  std::vector<std::string> names;
  if (p.has("names")) {
    const JsonReader nr = p.child("names");
    for (std::size_t i = 0, k = nr.require_array(); i < k; ++i) {
      if (!nr.at(i).value().is_string()) nr.at(i).fail("", "must be a particle name");
      names.push_back(nr.at(i).value().get<std::string>());
    }
  }
  std::vector<std::string> found;
  for (std::size_t i = 0; i < n; ++i) {
    const JsonReader r = list.at(i);
    ParticleSource s;
    s.name = r.string("name");
    if (!names.empty() && std::find(names.begin(), names.end(), s.name) == names.end()) continue;
    if (names.empty() && out.size() >= count) break;
    s.generated = geometry::read_particle_def(r);
    found.push_back(s.name);
    out.push_back(s);
  }
  for (const std::string& want : names) {
    if (std::find(found.begin(), found.end(), want) == found.end()) {
      p.fail("names", "\"" + want + "\" is not in " + set_file.string());
    }
  }
}

// "particles" (a set and/or meshes) and "orientations": the study's particles, each named once.
void read_particles(const JsonReader& r, const fs::path& base, StudyDef& s) {
  const JsonReader p = r.child("particles");
  p.require_object();
  p.only_keys({"set", "count", "names", "meshes"});
  if (p.has("set")) read_set(p, base, s.particles);
  if (p.has("meshes")) {
    const JsonReader list = p.child("meshes");
    for (std::size_t i = 0, n = list.require_array(); i < n; ++i) {
      const JsonReader m = list.at(i);
      m.only_keys({"name", "file", "scale"});
      ParticleSource src;
      if (m.string("file").empty()) m.fail("file", "must name a mesh file (got \"\")");
      src.file = base / m.string("file");
      src.name = m.has("name") ? m.string("name") : src.file.stem().string();
      if (m.has("scale")) src.scale = m.positive("scale");
      if (!fs::exists(src.file)) m.fail("file", "no such file " + src.file.string());
      s.particles.push_back(src);
    }
  }
  if (s.particles.empty()) p.fail("", "names no particle (give \"set\" or \"meshes\")");
  if (r.has("orientations")) {
    if (r.has("orientation")) {
      r.fail("orientations", "give either \"orientation\" or \"orientations\", not both");
    }
    const JsonReader o = r.child("orientations");
    o.require_object();
    o.only_keys({"random"});
    // Each orientation is a particle of its own, with its own reference: 64 is far above what a
    // study of 2 cores can run and keeps a typo from planning thousands of cases.
    s.orientations = static_cast<int>(o.integer("random", 1, 64));
    std::vector<ParticleSource> each;
    for (std::size_t i = 0; i < s.particles.size(); ++i) {
      for (int k = 0; k < s.orientations; ++k) {
        ParticleSource q = s.particles[i];
        q.name += "-o" + std::to_string(k + 1);
        q.orientation = k;
        q.source_index = i;
        each.push_back(std::move(q));
      }
    }
    s.particles = std::move(each);
  }
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    const std::string& n = s.particles[i].name;
    // The name is a file and folder under --out (particles/NAME.off, meshes/NAME-N/).
    if (const std::string problem = io::plain_name_problem(n); !problem.empty())
      p.fail("", "particle name " + io::echo(n) + ": " + problem);
    if (n.find(' ') != std::string::npos)
      p.fail("", "particle name " + io::echo(n) + ": must not contain spaces (a table cell)");
    for (std::size_t j = 0; j < i; ++j) {
      if (s.particles[j].name == n) p.fail("", "particle name \"" + n + "\" appears twice");
    }
  }
}

// "resolutions": even triangle counts, sorted, each once.
void read_resolutions(const JsonReader& r, StudyDef& s) {
  s.resolutions = {100, 250, 500, 1000, 2000};
  if (r.has("resolutions")) {
    const JsonReader list = r.child("resolutions");
    const std::size_t n = list.require_array();
    if (n == 0) list.fail("", "must list at least one resolution");
    s.resolutions.clear();
    for (std::size_t i = 0; i < n; ++i) {
      const Json& v = list.at(i).value();
      // A closed triangle mesh has an even face count (2F = 3E), and the simplifier reaches
      // exactly N only for even N (docs/geometry.md): an odd N would fail every case of it.
      if (!v.is_number_integer() || v.get<long long>() < 20 || v.get<long long>() > 1'000'000 ||
          v.get<long long>() % 2 != 0) {
        list.at(i).fail(
            "", "must be an even triangle count from 20 to 1000000 (got " + io::echo(v) + ")");
      }
      s.resolutions.push_back(v.get<long>());
    }
    std::sort(s.resolutions.begin(), s.resolutions.end());
    if (std::adjacent_find(s.resolutions.begin(), s.resolutions.end()) != s.resolutions.end()) {
      list.fail("", "lists a resolution twice");
    }
  }
  s.reference = s.resolutions.back();
}

// A key that lists names from a fixed set ("models", "placements"): a non-empty array, each entry
// a name `of` knows (an unknown one is refused with the names `expected`), and with `unique` none
// listed twice. Entries are checked in order, so the first bad one is the one named.
template <class T, class Of>
std::vector<T> read_names(const JsonReader& list, Of of, const std::string& expected,
                          const std::string& noun, bool unique) {
  std::vector<T> out;
  for (std::size_t i = 0, n = list.require_array(); i < n; ++i) {
    const Json& v = list.at(i).value();
    const std::optional<T> x = of(v.is_string() ? v.get<std::string>() : "");
    if (!x) list.at(i).fail("", "must be " + expected + " (got " + io::echo(v) + ")");
    out.push_back(*x);
    if (unique && std::count(out.begin(), out.end(), *x) > 1)
      list.at(i).fail("", "lists a " + noun + " twice");
  }
  if (out.empty()) list.fail("", "must list at least one " + noun);
  return out;
}

// "models": each once.
void read_models(const JsonReader& r, StudyDef& s) {
  s.models = {ModelKind::fem, ModelKind::rigid, ModelKind::sphere};
  if (r.has("models")) {
    s.models = read_names<ModelKind>(
        r.child("models"), model_of,
        "\"fem\", \"rigid\", \"rigid-penalty\", \"sphere\" or \"sphere-local\"", "model", true);
  }
}

// "placements".
void read_placements(const JsonReader& r, StudyDef& s) {
  s.placements = {Placement::centroid, Placement::lowest};
  if (r.has("placements")) {
    const auto placement_of = [](std::string_view name) -> std::optional<Placement> {
      if (name == "centroid") return Placement::centroid;
      if (name == "lowest") return Placement::lowest;
      return std::nullopt;
    };
    s.placements = read_names<Placement>(r.child("placements"), placement_of,
                                         "\"centroid\" or \"lowest\"", "placement", false);
  }
}

// "refinement": the refined element sizes and where they apply (after the resolutions and
// placements, which it names).
void read_refinement(const JsonReader& f, StudyDef& s) {
  f.require_object();
  f.only_keys({"sizes", "resolutions", "placements", "tolerance", "focus_radius", "growth",
               "max_contact_factor"});
  const JsonReader sizes = f.child("sizes");
  for (std::size_t i = 0, n = sizes.require_array(); i < n; ++i) {
    const Json& v = sizes.at(i).value();
    // Below 1e-3 R the tetrahedra (and the steps) would run to millions; above 1 the size is
    // not a refinement of any surface the study meshes.
    if (!v.is_number() || !(v.get<double>() >= 1e-3 && v.get<double>() <= 1)) {
      sizes.at(i).fail("", "must be a size over the equivalent radius from 0.001 to 1 (got " +
                               io::echo(v) + ")");
    }
    if (i > 0 && !(v.get<double>() < s.refinement.sizes.back())) {
      sizes.at(i).fail("", "must be smaller than the size before it (the sequence refines)");
    }
    s.refinement.sizes.push_back(v.get<double>());
  }
  if (f.has("resolutions")) {
    const JsonReader list = f.child("resolutions");
    for (std::size_t i = 0, n = list.require_array(); i < n; ++i) {
      const Json& v = list.at(i).value();
      if (!v.is_number_integer() || std::find(s.resolutions.begin(), s.resolutions.end(),
                                              v.get<long>()) == s.resolutions.end()) {
        list.at(i).fail("", "must be one of the study's resolutions (got " + io::echo(v) + ")");
      }
      s.refinement.resolutions.push_back(v.get<long>());
    }
  }
  if (f.has("placements")) {
    const JsonReader list = f.child("placements");
    for (std::size_t i = 0, n = list.require_array(); i < n; ++i) {
      const Json& v = list.at(i).value();
      const std::string m = v.is_string() ? v.get<std::string>() : "";
      const auto it = std::find_if(s.placements.begin(), s.placements.end(),
                                   [&](Placement q) { return m == placement_name(q); });
      if (it == s.placements.end())
        list.at(i).fail("", "must be one of the study's placements (got " + io::echo(v) + ")");
      s.refinement.placements.push_back(*it);
    }
  }
  if (f.has("tolerance")) s.refinement.tolerance = f.in_range("tolerance", 0, 0.5, true, false);
  if (f.has("focus_radius"))
    s.refinement.focus_radius = f.in_range("focus_radius", 0, 100, false, false);
  if (f.has("growth")) s.refinement.growth = f.in_range("growth", 0, 10, false, false);
  if (f.has("max_contact_factor")) {
    // As the scene key contact.max_contact_factor: 0 (none) or a factor of at least 1.
    const double c = f.in_range("max_contact_factor", 0, 1e6, false, false);
    if (c > 0 && c < 1) {
      f.fail("max_contact_factor",
             "must be 0 (no limit) or at least 1 (the contact cannot lengthen the elements' step)");
    }
    s.refinement.max_contact_factor = c;
  }
}

// The impact: "speed", "orientation", "gap", "duration", "end_after_separation",
// "penalty_alpha", "gravity".
void read_impact(const JsonReader& r, StudyDef& s) {
  if (r.has("speed")) s.speed = r.in_range("speed", 0, 1000, true, false);
  if (r.has("orientation")) {
    const Json& o = r.value()["orientation"];
    if (o.is_string()) {
      if (o != "random")
        r.fail("orientation",
               "must be [rx, ry, rz] in degrees or \"random\" (got " + io::echo(o) + ")");
      s.random_orientation = true;
    } else {
      s.orientation_deg = r.vec3("orientation");
    }
  }
  if (r.has("gap")) s.gap = r.in_range("gap", 0, 1, true, false);
  if (r.has("duration")) {
    const Json& d = r.value()["duration"];
    if (!(d.is_string() && d == "auto")) s.duration = r.in_range("duration", 0, 100, true, false);
  }
  if (r.has("end_after_separation")) {
    const Json& d = r.value()["end_after_separation"];
    s.end_after_separation = d.is_string() && d == "never"
                                 ? std::optional<double>()
                                 : r.in_range("end_after_separation", 0, 100, true, false);
  }
  // The scene's range (a case's scene is refused below it).
  if (r.has("penalty_alpha"))
    s.penalty_alpha = r.in_range("penalty_alpha", scene::kMinPenaltyAlpha, 1e6, false, false);
  if (r.has("gravity")) s.gravity = r.in_range("gravity", 0, 1000, false, false);
}

// "material" and "block_material" (a rock's by default).
void read_materials(const JsonReader& r, StudyDef& s) {
  const Material rock{
      .name = "particle", .density = 2650, .young = 5e10, .poisson = 0.25, .friction = 0};
  s.material = r.has("material") ? read_material(r.child("material"), "particle", rock) : rock;
  s.material.name = "particle";
  s.block_material =
      r.has("block_material") ? read_material(r.child("block_material"), "block", rock) : rock;
  s.block_material.name = "block";
}

// "reference" and the source reference's keys.
void read_reference(const JsonReader& r, StudyDef& s) {
  if (r.has("reference")) {
    const Json& v = r.value()["reference"];
    if (v == "source")
      s.reference_kind = ReferenceKind::source;
    else if (v != "finest")
      r.fail("reference", "must be \"source\" or \"finest\" (got " + io::echo(v) + ")");
  }
  for (const char* key : {"reference_patch_check", "reference_elements_across",
                          "reference_contact_mass", "reference_added_mass"}) {
    if (r.has(key) && s.reference_kind != ReferenceKind::source)
      r.fail(key, "applies only with \"reference\": \"source\"");
  }
  s.source_reference.patch_check = r.boolean_or("reference_patch_check", false);
  s.source_reference.contact_mass = r.boolean_or("reference_contact_mass", true);
  if (r.has("reference_added_mass")) {
    if (!s.source_reference.contact_mass)
      r.fail("reference_added_mass", "applies only with \"reference_contact_mass\": true");
    // 0: the refinement's factor as it is; below 1: a fraction of the body's mass.
    s.source_reference.added_mass = r.in_range("reference_added_mass", 0, 1, false, true);
  }
  // Fewer than 1 element across the contact radius resolves nothing of it; above 12 the finest
  // level's tetrahedra run past the scene loader's limit on the study's particles.
  if (r.has("reference_elements_across"))
    s.source_reference.elements_across =
        r.in_range("reference_elements_across", 1, 12, false, false);
  // The first round's three levels, and at most one more: a fifth would cost about 2.5 times the
  // fourth (docs/study.md, "The source reference").
  if (r.has("reference_max_levels")) {
    if (s.reference_kind != ReferenceKind::source)
      r.fail("reference_max_levels", "applies only with \"reference\": \"source\"");
    s.source_reference.max_levels = static_cast<int>(r.integer("reference_max_levels", 3, 4));
  }
}

}  // namespace

StudyDef load_study(const fs::path& file) {
  const Json json = io::read_json_file(file);
  const JsonReader r(json, file, "");
  r.require_object();
  r.only_keys({"name",
               "description",
               "particles",
               "particle_size",
               "resolutions",
               "models",
               "placements",
               "refinement",
               "speed",
               "orientation",
               "orientations",
               "gap",
               "duration",
               "end_after_separation",
               "penalty_alpha",
               "gravity",
               "material",
               "block_material",
               "rows",
               "jobs",
               "reference",
               "reference_patch_check",
               "reference_elements_across",
               "reference_contact_mass",
               "reference_added_mass",
               "reference_max_levels"});
  StudyDef s;
  s.file = file;
  s.name = r.has("name") ? r.string("name") : file.stem().string();
  const fs::path base = file.parent_path();

  read_particles(r, base, s);
  if (r.has("particle_size")) s.particle_size = r.positive("particle_size");
  read_resolutions(r, s);
  read_models(r, s);
  read_placements(r, s);
  if (r.has("refinement")) read_refinement(r.child("refinement"), s);
  read_impact(r, s);
  read_materials(r, s);
  read_reference(r, s);
  if (r.has("rows")) s.rows = static_cast<int>(r.integer("rows", 10, 1'000'000));
  if (r.has("jobs")) s.jobs = static_cast<int>(r.integer("jobs", 0, 1024));
  return s;
}

}  // namespace asperity::study

namespace asperity::study {

nlohmann::ordered_json material_json(const Material& m) {
  return {
      {"density", m.density}, {"young", m.young}, {"poisson", m.poisson}, {"friction", m.friction}};
}

namespace {

template <class T>
nlohmann::ordered_json optional_json(const std::optional<T>& v) {
  return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json();
}

}  // namespace

nlohmann::ordered_json definition_json(const StudyDef& def) {
  using OJson = nlohmann::ordered_json;
  OJson particles = OJson::array();
  for (const ParticleSource& p : def.particles) {
    OJson j = {{"name", p.name}};
    if (p.file.empty()) {
      const geometry::ParticleDef& g = p.generated;
      j.update({{"seed", g.seed},
                {"size", g.size},
                {"elongation", g.elongation},
                {"flatness", g.flatness},
                {"angularity", g.angularity},
                {"roughness", g.roughness},
                {"faces", g.faces}});
    } else {
      j.update({{"file", p.file.filename().string()}, {"scale", p.scale}});
    }
    if (p.orientation >= 0) j["orientation"] = p.orientation;
    particles.push_back(j);
  }
  OJson models = OJson::array(), placements = OJson::array();
  for (ModelKind m : def.models) models.push_back(model_name(m));
  for (Placement p : def.placements) placements.push_back(placement_name(p));
  OJson refine_placements = OJson::array();
  for (Placement p : def.refinement.placements) refine_placements.push_back(placement_name(p));
  const OJson refinement = {{"sizes", def.refinement.sizes},
                            {"resolutions", def.refinement.resolutions},
                            {"placements", refine_placements},
                            {"tolerance", def.refinement.tolerance},
                            {"focus_radius", def.refinement.focus_radius},
                            {"growth", def.refinement.growth},
                            {"max_contact_factor", def.refinement.max_contact_factor}};
  OJson out = {{"name", def.name},
               {"particles", particles},
               {"particle_size", optional_json(def.particle_size)},
               {"resolutions", def.resolutions},
               {"models", models},
               {"placements", placements},
               {"refinement", refinement},
               {"speed", def.speed},
               {"orientation", def.random_orientation
                                   ? OJson("random")
                                   : OJson{def.orientation_deg.x(), def.orientation_deg.y(),
                                           def.orientation_deg.z()}},
               {"gap", def.gap},
               {"duration", def.duration ? OJson(*def.duration) : OJson("auto")},
               {"end_after_separation",
                def.end_after_separation ? OJson(*def.end_after_separation) : OJson("never")},
               {"penalty_alpha", optional_json(def.penalty_alpha)},
               {"gravity", def.gravity},
               {"material", material_json(def.material)},
               {"block_material", material_json(def.block_material)},
               {"rows", def.rows}};
  // Only when given: the folders of studies without it keep their study.json.
  if (def.orientations > 0) out["orientations"] = {{"random", def.orientations}};
  if (def.reference_kind == ReferenceKind::source) {
    out["reference"] = reference_name(def.reference_kind);
    out["reference_patch_check"] = def.source_reference.patch_check;
    out["reference_elements_across"] = def.source_reference.elements_across;
    // Both always: a folder run with another contact fix or budget (face-penalty, the default
    // until 7 December 2026; mass without a budget) has other levels and is refused.
    out["reference_contact_mass"] = def.source_reference.contact_mass;
    if (def.source_reference.contact_mass) {
      out["reference_added_mass"] = def.source_reference.added_mass;
    }
  }
  // Only when not the default 4: the folders of source studies keep their study.json.
  if (def.reference_kind == ReferenceKind::source && def.source_reference.max_levels != 4)
    out["reference_max_levels"] = def.source_reference.max_levels;
  return out;
}

std::string first_difference(const nlohmann::json& a, const nlohmann::json& b,
                             const std::string& path) {
  const auto shown = [](const nlohmann::json& v) {
    const std::string s = v.dump();
    return s.size() <= 60 ? s : s.substr(0, 57) + "...";
  };
  const std::string key = path.empty() ? "the definition" : "\"" + path + "\"";
  if (a.is_object() && b.is_object()) {
    for (const auto& [k, v] : a.items()) {
      const std::string sub = path.empty() ? k : path + "." + k;
      if (!b.contains(k)) return "\"" + sub + "\" is " + shown(v) + " there, absent here";
      if (std::string d = first_difference(v, b.at(k), sub); !d.empty()) return d;
    }
    for (const auto& [k, v] : b.items()) {
      const std::string sub = path.empty() ? k : path + "." + k;
      if (!a.contains(k)) return "\"" + sub + "\" is absent there, " + shown(v) + " here";
    }
    return "";
  }
  if (a.is_array() && b.is_array() && a.size() == b.size()) {
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (std::string d = first_difference(a[i], b[i], path + "[" + std::to_string(i) + "]");
          !d.empty())
        return d;
    }
    return "";
  }
  return a == b ? "" : key + " is " + shown(a) + " there, " + shown(b) + " here";
}

}  // namespace asperity::study
