// The study runner: sources → meshes → cases, each phase in a pool of worker threads.
#include "study/study_run.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "cluster/task_pool.hpp"
#include "solver/contact/hertz_impact.hpp"
#include "solver/core/clock.hpp"
#include "solver/core/error.hpp"
#include "solver/core/format.hpp"
#include "solver/fdem/fdem_world.hpp"
#include "solver/fdem/time_step.hpp"
#include "solver/geometry/contact_local_surface.hpp"
#include "solver/geometry/element_size.hpp"
#include "solver/geometry/mass_properties.hpp"
#include "solver/geometry/mesh_pipeline.hpp"
#include "solver/geometry/write_mesh.hpp"
#include "solver/io/atomic_file.hpp"
#include "solver/io/json_file.hpp"
#include "solver/run/prepared_meshes.hpp"
#include "solver/run/run_scene.hpp"
#include "solver/scene/scene.hpp"
#include "solver/scene/write_scene.hpp"
#include "study/case_weight.hpp"
#include "study/source_reference.hpp"
#include "study/study_meshes.hpp"
#include "study/tables/study_cases.hpp"

namespace asperity::study {
namespace fs = std::filesystem;
using OJson = nlohmann::ordered_json;
using StopAt = std::optional<std::chrono::steady_clock::time_point>;

namespace {

// Whether the caller's deadline (StudyRunOptions::stop_at) has passed.
bool past(const StopAt& stop_at) {
  return stop_at && std::chrono::steady_clock::now() >= *stop_at;
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return {};
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A contact still open when a case's window ends is no result: the run ended by its duration
// with force on the particle at its last step, so its peak, impulse and duration are a cut
// curve's. The study's "auto" window (plan_particles: the approach plus 1.5 Hertz contact times)
// was cut by the rigid model's softer contacts at sharp strike points: 34 of the 40 rigid cases
// of reports/study-wide-source ended so, ballast_01-o1's at all five resolutions with the force
// at its last step its largest (docs/study.md, "Contacts the window cut"). Such a case runs again
// with its window doubled, up to kMaxWindowDoublings times, and fails if it is still open then.
// The run in a doubled window is the same run continued (its sampling is set from the first
// window): every case that closed in the first window is unchanged to the bit.
constexpr int kMaxWindowDoublings = 3;

bool contact_open_at_end(const std::string& ended_by, double last_force) {
  return ended_by == "duration" && last_force > 0;
}
bool contact_open_at_end(const run::RunResult& r) {
  return r.status == "ok" && !r.force.empty() &&
         contact_open_at_end(r.summary.value("ended_by", std::string()), r.force.back().f);
}
// The same of a case an earlier run left as done (its summary.json and force.csv's last row).
bool stored_contact_open_at_end(const fs::path& dir) {
  try {
    const OJson summary = OJson::parse(read_text(dir / "summary.json"));
    if (summary.value("status", std::string()) != "ok") return false;
    const tables::Curve curve = tables::read_force(dir / "force.csv");
    return !curve.f.empty() &&
           contact_open_at_end(summary.value("ended_by", std::string()), curve.f.back());
  } catch (const std::exception&) {
    return false;  // unreadable: the case is as the earlier run left it (the tables name it)
  }
}

// What makes a particle's source surface: the meshes of an earlier run are reused only when it
// matches.
std::string source_tag(const StudyDef& def, const ParticleSource& p, std::size_t index) {
  std::ostringstream s;
  s.precision(17);
  if (p.file.empty()) {
    const geometry::ParticleDef& g = p.generated;
    s << "generated seed=" << g.seed << " size=" << g.size << " elongation=" << g.elongation
      << " flatness=" << g.flatness << " angularity=" << g.angularity
      << " roughness=" << g.roughness << " faces=" << g.faces;
  } else {
    s << "file=" << fs::absolute(p.file).string() << " scale=" << p.scale
      << " mtime=" << fs::last_write_time(p.file).time_since_epoch().count();
  }
  s << " particle_size=" << (def.particle_size ? *def.particle_size : 0.0);
  if (p.orientation >= 0) {
    s << " orientation=random#" << p.source_index << "/" << p.orientation;
  } else if (def.random_orientation) {
    s << " orientation=random#" << index;
  } else {
    s << " orientation=" << def.orientation_deg.x() << "," << def.orientation_deg.y() << ","
      << def.orientation_deg.z();
  }
  return s.str();
}

std::string clock_text(double s) {
  char buf[32];
  if (s >= 3600) {
    std::snprintf(buf, sizeof buf, "%dh%02dm", static_cast<int>(s / 3600),
                  static_cast<int>(s / 60) % 60);
  } else {
    std::snprintf(buf, sizeof buf, "%dm%02ds", static_cast<int>(s / 60), static_cast<int>(s) % 60);
  }
  return buf;
}

// Progress on rank 0's stderr, across every rank: a line redrawn in place on a terminal, else one
// line every 10 s. Fed by the task pool's reports, one at a time.
class Progress {
 public:
  Progress(bool quiet, std::string what, int total, double total_weight, bool ranks)
      : quiet_(quiet),
        tty_(isatty(2) != 0),
        ranks_(ranks),
        what_(std::move(what)),
        total_(total),
        total_weight_(total_weight) {
    // Said at once: the first report may be minutes away (a fine mesh, a refined case).
    if (!quiet_ && total_ > 0) std::fprintf(stderr, "%s: %d to do\n", what_.c_str(), total_);
  }
  // A task of relative cost `weight` reported; `running`: tasks handed out and not yet reported.
  // A task kept from an earlier run leaves the time-left estimate (its weight took no time).
  void done(const cluster::TaskReport& r, double weight, int running) {
    ++count_;
    failed_ += r.failed ? 1 : 0;
    (r.skipped || r.postponed ? total_weight_ -= weight : weight_ += weight);
    if (quiet_) return;
    const double el = elapsed();
    if (!tty_ && el - last_print_ < 10 && count_ < total_) return;
    last_print_ = el;
    const double left = weight_ > 0 ? el * (total_weight_ - weight_) / weight_ : 0;
    const std::string failed = failed_ > 0 ? ", " + std::to_string(failed_) + " failed" : "";
    const std::string where = ranks_ ? ", rank " + std::to_string(r.rank) : "";
    std::fprintf(stderr, "%s%s [%d/%d] %d running%s  %s elapsed, ~%s left  (%s%s)%s",
                 tty_ ? "\r\033[K" : "", what_.c_str(), count_, total_, running, failed.c_str(),
                 clock_text(el).c_str(), clock_text(left).c_str(), r.note.c_str(), where.c_str(),
                 tty_ ? "" : "\n");
    if (tty_ && count_ == total_) std::fprintf(stderr, "\n");
  }
  double elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  bool quiet_, tty_, ranks_;
  std::string what_;
  int total_;
  double total_weight_;
  int count_ = 0, failed_ = 0;
  double weight_ = 0, last_print_ = -1e9;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

fs::path mesh_dir(const fs::path& out, const std::string& particle, long faces) {
  return out / "meshes" / particle / std::to_string(faces);
}
// The source reference's contact-local surface: patch 1 (the patch) or 2 (doubled).
fs::path source_mesh_dir(const fs::path& out, const std::string& particle, int patch) {
  return out / "meshes" / particle / (patch == 1 ? "source" : "source-patch2");
}

// Per particle, from its meshes: where each case starts and how long every case runs.
struct ParticlePlan {
  std::map<long, double> centroid_height;   // centroid above the lowest vertex, per resolution, m
  std::map<long, Vec3> lowest_point;        // the strike point, surface.off's coordinates, m
  std::map<long, double> dt_fem, dt_rigid;  // estimated steps (for the rows kept), s
  double radius = 0, mass = 0;              // volume-equivalent sphere of the reference mesh
  // "sphere-local": Hertz's equivalent radius √(R1 R2) at the reference mesh's lowest vertex
  // (geometry/local_curvature.hpp; 0 where the surface there is flat or concave), and its
  // principal radii (m).
  double local_radius = 0, local_r1 = 0, local_r2 = 0;
  double duration = 0, contact_time = 0;  // s
  std::string mesh_error;                 // non-empty: a resolution failed to mesh
  // The source reference's surfaces, by patch (1, 2), from their mesh.json.
  struct Source {
    Vec3 strike_point = Vec3::Zero();  // surface.off's coordinates, m
    double centroid_height = 0;        // centroid above the strike point, m
    double radius = 0;                 // the source's equivalent radius, m
    std::vector<double> sizes;         // element sizes at the strike point, m, coarsest first
  };
  std::map<int, Source> source;
  std::string source_error;  // non-empty: a source reference surface failed
};

// Height of the centroid of case c above the block top (z = 0), and the gap under its lowest
// point. "centroid": every resolution's centroid at one height (the published study's
// placement), the height at which the lowest point of the lowest-reaching mesh sits `gap` above
// the block: Lindstrom–Turk keeps the volume, so a coarse mesh may reach below the reference
// as well as lose its lowest asperity. "lowest": each mesh's own lowest point `gap` above the
// block. The sphere's centre goes where the particle's centroid is, but never closer than `gap`
// to the block.
std::pair<double, double> start_height(const StudyDef& def, const ParticlePlan& pp,
                                       const CaseKey& c) {
  double reach = 0;
  for (const auto& [n, h] : pp.centroid_height) reach = std::max(reach, h);
  // The particle itself (the source reference's surfaces) reaches as low as any simplification.
  for (const auto& [patch, src] : pp.source) reach = std::max(reach, src.centroid_height);
  const double ref = def.gap + reach;
  if (c.source_patch > 0) {
    const double h = pp.source.at(c.source_patch).centroid_height;
    const double z = c.placement == Placement::centroid ? ref : def.gap + h;
    return {z, z - h};
  }
  if (c.model == ModelKind::sphere) {
    const double z = c.placement == Placement::centroid ? std::max(ref, def.gap + pp.radius)
                                                        : def.gap + pp.radius;
    return {z, z - pp.radius};
  }
  if (c.model == ModelKind::sphere_local) {
    // Its lowest point where the reference mesh's is: `gap` above the block ("lowest"), or as
    // the reference mesh sits under the centroid placement.
    const double low =
        c.placement == Placement::centroid ? ref - pp.centroid_height.at(def.reference) : def.gap;
    return {low + pp.local_radius, low};
  }
  const double h = pp.centroid_height.at(c.resolution);
  const double z = c.placement == Placement::centroid ? ref : def.gap + h;
  return {z, z - h};
}

// The block every model strikes is rigid: the fem model's potential contact presses the particle
// into a fixed block that does not deform (penalty α·E of the particle alone, fdem_world.cpp),
// whereas the Hertz sphere and the volume-hertz polyhedron take E* from both materials, which
// for a block of the particle's material halves E* (peak force 2^0.4 = 1.32 times lower, contact
// 1.32 times longer than the fem's for the same geometry). Those models' block gets a Young's
// modulus kRigidBlock times its own, so E* = E/(1 − ν²) of the particle to 1e-6 relative.
constexpr double kRigidBlock = 1e6;
Material named(Material m, const std::string& name) {
  m.name = name;
  return m;
}
Material block_material(const StudyDef& def, ModelKind m) {
  Material b = named(def.block_material, "block");
  if (is_sphere(m) || m == ModelKind::rigid) b.young = kRigidBlock * def.block_material.young;
  return b;
}

// The case's scene: the particle (a sphere, or its mesh at the case's resolution and element size,
// out/meshes/P/N/surface.off) above the rigid block, in the model's contact law. Written as the
// case's scene.json (scene::scene_json), which is what runs.
scene::SceneDef case_scene(const StudyDef& def, const fs::path& out, const ParticlePlan& pp,
                           const CaseKey& c) {
  const double z = start_height(def, pp, c).first;
  const double half = 2 * pp.radius + 0.01,
               depth = 2 * pp.radius + 0.01;  // block: wider than the particle
  scene::SceneDef s;
  s.name = c.particle + "-" + c.dir_name();
  s.gravity = Vec3(0, 0, -def.gravity);
  s.duration = pp.duration;
  s.materials = {named(def.material, "particle"), block_material(def, c.model)};
  scene::BodyDef particle{.name = "particle", .material = 0};
  int every = 1;
  if (c.model == ModelKind::sphere) {
    particle.shape = scene::SphereShape{.radius = pp.radius};
  } else if (c.model == ModelKind::sphere_local) {
    // The particle's mass on a sphere of the local radius: its own material.
    Material local = named(def.material, "particle-local");
    local.density = pp.mass / (4.0 / 3.0 * std::numbers::pi * std::pow(pp.local_radius, 3));
    s.materials.push_back(local);
    particle.shape = scene::SphereShape{.radius = pp.local_radius};
    particle.material = 2;
  } else {
    scene::MeshShape mesh{.file = out / "meshes" / c.particle / std::to_string(c.resolution) /
                                  "surface.off"};
    particle.model = c.model == ModelKind::fem ? scene::Model::fem : scene::Model::rigid;
    double dt = (c.model == ModelKind::fem ? pp.dt_fem : pp.dt_rigid).at(c.resolution);
    if (c.level > 0) {
      // Graded towards the strike point: h there, growing at the study's rate beyond
      // focus_radius·h (the Hertz gate's grading, reports/fem/hertz_convergence.md).
      const double h = c.relative_size * pp.radius;
      mesh.element_size = h;
      mesh.element_size_focus = pp.lowest_point.at(c.resolution);
      mesh.element_size_focus_radius = def.refinement.focus_radius * h;
      mesh.element_size_growth = def.refinement.growth;
      // The rows kept: the step falls about as h over the surface edge (case_weight).
      dt *= std::min(1.0, c.relative_size / std::sqrt(29.0 / static_cast<double>(c.resolution)));
    }
    particle.shape = mesh;
    every = static_cast<int>(std::max(1L, static_cast<long>(pp.duration / dt / def.rows)));
  }
  particle.position = Vec3(0, 0, z);
  particle.velocity = Vec3(0, 0, -def.speed);
  s.bodies = {
      particle,
      {.name = "block",
       .material = 1,
       .shape = scene::BoxShape{.min = Vec3(-half, -half, -depth), .max = Vec3(half, half, 0)},
       .fixed = true}};
  s.contact.law = is_sphere(c.model)            ? scene::ContactLaw::hertz
                  : c.model == ModelKind::rigid ? scene::ContactLaw::volume_hertz
                                                : scene::ContactLaw::potential;
  if (def.penalty_alpha && (c.model == ModelKind::fem || c.model == ModelKind::rigid_penalty)) {
    s.contact.penalty_alpha = *def.penalty_alpha;
  }
  if (c.level > 0 && def.refinement.max_contact_factor > 0) {
    // A graded mesh's small surface faces under the study's explicit penalty can set a step far
    // below the elements' (rock_02 at growth 0.15: 1.26e-9 s against 3.6e-8 s); the factor lowers
    // the penalty of those faces alone (face-penalty, the scene default's way).
    s.contact.max_contact_factor = def.refinement.max_contact_factor;
  }
  s.record = {.body = 0, .every = every};
  if (def.end_after_separation && !is_sphere(c.model)) {
    s.record.end_after_separation = *def.end_after_separation * pp.contact_time;
  }
  return s;
}

// A source reference case's scene: the contact-local surface of its patch, refined at the strike
// point to the level's size and graded as the study's refinement (focus_radius, growth,
// max_contact_factor), on the fem path of every refined case: the same block, penalty, record and
// end (study/source_reference.hpp; docs/study.md, "The source reference").
scene::SceneDef source_case_scene(const StudyDef& def, const fs::path& out, const ParticlePlan& pp,
                                  const CaseKey& c) {
  const ParticlePlan::Source& src = pp.source.at(c.source_patch);
  const double h = level_size(src.sizes, c.level);
  // The fem case's scene at the finest resolution with the mesh, start and rows swapped: one path.
  CaseKey coarse = c;
  coarse.source_patch = 0;
  coarse.level = 0;
  coarse.resolution = def.reference;
  scene::SceneDef s = case_scene(def, out, pp, coarse);
  s.name = c.particle + "-" + c.dir_name();
  scene::BodyDef& particle = s.bodies.front();
  particle.position = Vec3(0, 0, start_height(def, pp, c).first);
  scene::MeshShape mesh{.file = source_mesh_dir(out, c.particle, c.source_patch) / "surface.off"};
  mesh.element_size = h;
  mesh.element_size_focus = src.strike_point;
  mesh.element_size_focus_radius = def.refinement.focus_radius * h;
  mesh.element_size_growth = def.refinement.growth;
  particle.shape = mesh;
  // The rows kept: the step falls about as h over the reference mesh's surface edge (case_weight).
  const double dt =
      pp.dt_fem.at(def.reference) *
      std::min(1.0, h / pp.radius / std::sqrt(29.0 / static_cast<double>(def.reference)));
  s.record.every = static_cast<int>(std::max(1L, static_cast<long>(pp.duration / dt / def.rows)));
  if (def.refinement.max_contact_factor > 0) {
    s.contact.max_contact_factor = def.refinement.max_contact_factor;
  }
  // "reference_contact_mass": the factor met by contact mass, not by lowering the penalty of the
  // faces that set the step (the study's own refined cases): at a sharp strike point those faces
  // are the contact's, and face-penalty lowered them to 3.6-4.6 % of α, let the tip sink 25-77 µm
  // into the block (a fifth of a level's element) and Munjiza's potential then fed energy in until
  // an element inverted, at the same time at half the step (ballast_01-o1 and ballast_03-o1 of
  // data/study/wide-source.json, 7 December 2026; docs/study.md, "The wider study against the
  // particle"). With mass the penalty stays as asked (ballast_01-o1's levels sink 3-9 µm), 1e-5 to
  // 2.5e-3 of the body's mass is added at the surface nodes (a Hertz peak moves by 3/5 of it, less
  // at each finer level, so the limit carries none of it), and the same levels run stable.
  if (def.source_reference.contact_mass) {
    s.contact.contact_factor_by = scene::ContactFactorBy::mass;
    // The factor lowered within a mass budget (StudyDef::source_reference.added_mass): the
    // levels' step is otherwise the contact's, 2.6 times below their elements'.
    if (def.source_reference.added_mass > 0 && s.contact.max_contact_factor) {
      s.contact.max_added_mass = def.source_reference.added_mass;
    }
  }
  return s;
}

// Keeps about `rows` force and energy rows (every k-th, and the last): the summary's measures
// come from every step; the rows are for the charts.
void thin_rows(run::RunResult& r, int rows) {
  const std::size_t n = r.force.size();
  if (n <= static_cast<std::size_t>(2 * rows)) return;
  const std::size_t k = n / static_cast<std::size_t>(rows);
  std::vector<run::ForceRow> f;
  std::vector<run::EnergyRow> e;
  for (std::size_t i = 0; i < n; i += k) {
    f.push_back(r.force[i]);
    if (i < r.energy.size()) e.push_back(r.energy[i]);
  }
  if (f.back().t != r.force.back().t) {
    f.push_back(r.force.back());
    if (!r.energy.empty()) e.push_back(r.energy.back());
  }
  r.force = std::move(f);
  r.energy = std::move(e);
}

// Predicted critical step of the particle (fem or rigid) above the block, times the runners'
// default safety (run/step_policy.hpp): only used to keep about `rows` rows per case. Not
// run::predicted_step: it runs at the mesh step, before any case scene exists, on the prepared
// tetrahedra, the block's own material and the potential law for both kinds, where the case runs
// volume-hertz against a block 1e6 times stiffer for rigid and re-meshes surface.off. Measured on
// tests/study/smoke_study.json: the run's dt is 0.91-1.07 of this for fem, 0.002-0.009 for rigid
// (so rigid cases record 100-400 times the rows asked for before thin_rows). It is not scheduling
// alone: it sets the case scene's record.every, so the rows of force.csv that the curve measures
// and the tables read; run::predicted_step in its place would move them.
double estimated_dt(const TetMesh& tets, const StudyDef& def, fdem::BodyKind kind, double radius) {
  const fdem::World world = fdem::make_world(particle_on_block(tets, def, kind, radius));
  return run::default_safety(kind == fdem::BodyKind::rigid ? run::StepRegime::fdem_rigid
                                                           : run::StepRegime::fdem_deformable) *
         fdem::critical_step(world).critical;
}

}  // namespace

std::string CaseKey::dir_name() const {
  if (source_patch > 0) {
    return std::string(source_patch == 1 ? "source-L" : "source-patch2-L") + std::to_string(level) +
           "-" + placement_name(placement);
  }
  if (model == ModelKind::sphere) return std::string("sphere-") + placement_name(placement);
  if (model == ModelKind::sphere_local)
    return std::string("sphere-local-") + placement_name(placement);
  std::string level_part;
  if (level > 0) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "h%g-", relative_size);
    level_part = buf;
  }
  return std::string(model_name(model)) + "-" + std::to_string(resolution) + "-" + level_part +
         placement_name(placement);
}

fs::path case_dir(const fs::path& out, const CaseKey& key) {
  return out / "cases" / key.particle / key.dir_name();
}

int unfinished_cases(const StudyDef& def, const fs::path& out) {
  int n = 0;
  for (const auto& plan : {plan_cases(def), plan_source_cases(def, out)}) {
    for (const CaseKey& k : plan) {
      const fs::path dir = case_dir(out, k);
      n += !fs::exists(dir / "case.json") && !fs::exists(dir / "failed.json");
    }
  }
  return n;
}

std::vector<CaseKey> plan_cases(const StudyDef& def) {
  std::vector<CaseKey> out;
  for (const ParticleSource& p : def.particles) {
    for (ModelKind m : def.models) {
      if (is_sphere(m)) {
        for (Placement pl : def.placements) out.push_back({p.name, m, 0, pl});
        continue;
      }
      for (long n : def.resolutions) {
        for (Placement pl : def.placements) {
          out.push_back({p.name, m, n, pl});
          if (m != ModelKind::fem || !def.refinement.applies(n, pl)) continue;
          for (std::size_t k = 0; k < def.refinement.sizes.size(); ++k) {
            out.push_back({p.name, m, n, pl, static_cast<int>(k + 1), def.refinement.sizes[k]});
          }
        }
      }
    }
  }
  return out;
}

namespace {

CaseKey source_key(const std::string& particle, Placement pl, int patch, int level) {
  return {.particle = particle,
          .model = ModelKind::fem,
          .resolution = 0,
          .placement = pl,
          .level = level,
          .source_patch = patch};
}

// Per particle and placement, its levels on each patch (`levels_of` of them), coarsest first.
std::vector<CaseKey> source_cases(
    const StudyDef& def, const std::function<int(const std::string&, Placement)>& levels_of) {
  std::vector<CaseKey> out;
  if (def.reference_kind != ReferenceKind::source) return out;
  const int patches = def.source_reference.patch_check ? 2 : 1;
  for (const ParticleSource& p : def.particles) {
    for (Placement pl : def.placements) {
      const int levels = levels_of(p.name, pl);
      for (int patch = 1; patch <= patches; ++patch) {
        for (int level = 1; level <= levels; ++level)
          out.push_back(source_key(p.name, pl, patch, level));
      }
    }
  }
  return out;
}

// A finished level on the patch: its size over the source's R (case.json element_size_rel) and
// its peak force (source_level of summary.json's peak_force_filtered), as the tables read them
// (tables::source_reference_of); none unless case.json is written, the status is "ok" and both
// are numbers.
std::optional<std::pair<double, double>> finished_level(const fs::path& out, const CaseKey& k) {
  const fs::path dir = case_dir(out, k);
  if (!fs::exists(dir / "case.json") || !fs::exists(dir / "summary.json")) return std::nullopt;
  const io::Json summary = io::read_json_file(dir / "summary.json");
  const io::Json record = io::read_json_file(dir / "case.json");
  const auto number = [](const io::Json& j, const char* key) {
    return j.contains(key) && j[key].is_number() ? j[key].get<double>() : std::nan("");
  };
  const double size = number(record, "element_size_rel");
  const double peak = source_level(number(summary, "peak_force_filtered"), 0, 0).peak_force;
  if (summary.value("status", "") != "ok" || !std::isfinite(size) || !std::isfinite(peak))
    return std::nullopt;
  return std::pair{size, peak};
}

// How many levels one particle and placement has in OUT: the first round's, one more each time
// every level so far finished on the patch with a peak force that wants a finer one
// (wants_finer_level), up to the study's reference_max_levels.
int source_levels_in(const StudyDef& def, const fs::path& out, const std::string& particle,
                     Placement pl) {
  int planned = SourceReferenceOptions{}.levels;
  std::vector<double> sizes, peaks;
  for (int level = 1; level <= planned; ++level) {
    const auto l = finished_level(out, source_key(particle, pl, 1, level));
    if (!l) break;
    sizes.push_back(l->first);
    peaks.push_back(l->second);
    if (level == planned && planned < def.source_reference.max_levels &&
        wants_finer_level(sizes, peaks))
      ++planned;
  }
  return planned;
}

}  // namespace

std::vector<CaseKey> plan_source_cases(const StudyDef& def) {
  return source_cases(
      def, [](const std::string&, Placement) { return SourceReferenceOptions{}.levels; });
}

std::vector<CaseKey> plan_source_cases(const StudyDef& def, const fs::path& out) {
  return source_cases(def, [&](const std::string& particle, Placement pl) {
    return source_levels_in(def, out, particle, pl);
  });
}

Shard parse_shard(const std::string& text) {
  const auto fail = [&](const std::string& why) -> Shard {
    throw InputError("--shard: " + why + " (got \"" + text +
                     "\"; K/N runs the K-th of N shards, "
                     "1 <= K <= N)");
  };
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos) return fail("must be K/N");
  int k = 0, n = 0;
  try {
    std::size_t used_k = 0, used_n = 0;
    k = std::stoi(text.substr(0, slash), &used_k);
    n = std::stoi(text.substr(slash + 1), &used_n);
    if (used_k != slash || used_n != text.size() - slash - 1) return fail("must be K/N");
  } catch (const std::logic_error&) {
    return fail("K and N must be whole numbers");
  }
  if (n < 1) return fail("N must be at least 1");
  if (k < 1 || k > n) return fail("K must be from 1 to N");
  return {.index = k, .count = n};
}

std::vector<std::size_t> shard_particles(const StudyDef& def, const Shard& shard) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < def.particles.size(); ++i) {
    if (shard.count == 0 ||
        static_cast<int>(i % static_cast<std::size_t>(shard.count)) == shard.index - 1) {
      out.push_back(i);
    }
  }
  return out;
}

FolderLock::FolderLock(const fs::path& out, const Shard& shard) {
  // A whole run excludes everything else; shards share the study lock and each holds its own.
  const auto take = [this](const fs::path& file, int how, const std::string& who) {
    for (int attempt = 0; attempt < 3; ++attempt) {
      const int fd = ::open(file.c_str(), O_CREAT | O_RDWR, 0644);
      if (fd < 0 || ::flock(fd, how | LOCK_NB) != 0) {
        if (fd >= 0) ::close(fd);
        throw InputError(file.parent_path().string() + ": " + who + " is running in this folder");
      }
      // A study that just ended removed the file we locked (see the destructor): take a new one.
      struct stat held {};
      struct stat named {};
      if (::fstat(fd, &held) == 0 && ::stat(file.c_str(), &named) == 0 &&
          held.st_ino == named.st_ino) {
        fds_.push_back(fd);
        files_.push_back(file);
        return;
      }
      ::close(fd);
    }
    throw std::runtime_error(file.string() + ": cannot take the lock");
  };
  take(out / "study.lock", shard.count == 0 ? LOCK_EX : LOCK_SH, "another asperity study");
  if (shard.count > 0) {
    const std::string name = std::to_string(shard.index) + "-of-" + std::to_string(shard.count);
    take(out / ("shard-" + name + ".lock"), LOCK_EX, "shard " + name);
  }
  // SIGINT/SIGTERM remove the locks this process alone holds (a shared study.lock stays).
  for (std::size_t i = shard.count == 0 ? 0 : 1; i < files_.size(); ++i)
    on_interrupt_.push_back(std::make_unique<RemoveOnInterrupt>(files_[i]));
}

FolderLock::~FolderLock() {
  // However the study ends (an exception, exit 2 included), a lock no one else holds goes: an
  // exclusive hold is taken first, so a shard still running keeps the shared study.lock.
  for (std::size_t i = 0; i < fds_.size(); ++i) {
    if (::flock(fds_[i], LOCK_EX | LOCK_NB) == 0) ::unlink(files_[i].c_str());
    ::close(fds_[i]);
  }
}

void adopt_folder(const StudyDef& def, const fs::path& out) {
  const fs::path file = out / "study.json";
  const io::Json mine = io::Json::parse(definition_json(def).dump());
  if (fs::exists(file)) {
    const io::Json theirs = io::read_json_file(file);
    const std::string where = first_difference(theirs, mine);
    if (!where.empty()) {
      throw InputError(file.string() + ": " + where + " in " + def.file.string() +
                       ": this folder holds another study definition's cases (use another --out, "
                       "or remove the folder)");
    }
    return;
  }
  fs::create_directories(out);
  io::write_atomically(file, definition_json(def).dump(1) + "\n");
}

namespace {

int thread_count(const StudyDef& def, const StudyRunOptions& options) {
  if (options.jobs > 0) return options.jobs;
  if (def.jobs > 0) return def.jobs;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

// Phase 1, sources (cheap, every rank): each particle's surface, centred, scaled and rotated.
std::vector<SurfaceMesh> make_sources(const StudyDef& def,
                                      const std::vector<std::size_t>& particles) {
  std::vector<SurfaceMesh> sources(def.particles.size());
  for (std::size_t i : particles) sources[i] = particle_source(def, i);
  return sources;
}

// What the study asks of each particle that can be known from its source, checked before the
// lock and any mesh or case (issue 31, classes 8 and 11):
// - every resolution at most the source's triangle count (simplification only removes
//   triangles; every case of the particle failed after the run, and complete-looking tables
//   were written);
// - the finest refinement's estimated tetrahedra within the scene loader's limit (a refined case
//   meshed for minutes in silence, then failed), graded as the case's scene grades it.
void check_before_run(const StudyDef& def, const std::vector<std::size_t>& particles,
                      const std::vector<SurfaceMesh>& sources) {
  const bool polyhedra =
      std::any_of(def.models.begin(), def.models.end(), [](ModelKind k) { return !is_sphere(k); });
  for (std::size_t i : particles) {
    const long have = static_cast<long>(sources[i].faces.cols());
    for (std::size_t k = 0; k < def.resolutions.size(); ++k) {
      const long n = def.resolutions[k];
      if ((polyhedra || n == def.reference) && n > have) {
        throw InputError(def.file.string() + ": resolutions[" + std::to_string(k) +
                         "]: " + std::to_string(n) + " triangles is more than particle \"" +
                         def.particles[i].name + "\" has (" + std::to_string(have) +
                         "); a particle is only ever simplified");
      }
    }
    const bool fem =
        std::find(def.models.begin(), def.models.end(), ModelKind::fem) != def.models.end();
    if (!fem || def.refinement.sizes.empty()) continue;
    const double radius = geometry::mass_properties(sources[i]).equivalent_radius;
    Eigen::Index lowest = 0;
    sources[i].vertices.row(2).minCoeff(&lowest);
    const double h = def.refinement.sizes.back() * radius;
    const geometry::ElementSize size{.size = h,
                                     .focus = sources[i].vertices.col(lowest),
                                     .focus_radius = def.refinement.focus_radius * h,
                                     .growth = def.refinement.growth};
    if (const std::string problem = geometry::element_size_problem(sources[i], size);
        !problem.empty()) {
      throw InputError(def.file.string() + ": refinement.sizes[" +
                       std::to_string(def.refinement.sizes.size() - 1) + "]: particle \"" +
                       def.particles[i].name + "\": " + problem);
    }
  }
}

// Rank 0 writes the sources for the record.
void write_sources(const StudyDef& def, const fs::path& out,
                   const std::vector<std::size_t>& particles,
                   const std::vector<SurfaceMesh>& sources) {
  for (std::size_t i : particles) {
    const fs::path f = out / "particles" / (def.particles[i].name + ".off");
    fs::create_directories(f.parent_path());
    geometry::write_surface_mesh(f, sources[i]);
  }
}

struct MeshTask {
  std::size_t particle;
  long faces;            // 0 for the source reference's surfaces
  int source_patch = 0;  // 1, 2: the source reference's surface on the patch, doubled patch
};
struct Meshes {
  std::vector<MeshTask> tasks;
  std::vector<std::string> errors;  // per task; empty: meshed (now or by an earlier run)
  int postponed = 0;                // tasks not run: the deadline had passed
};

// One mesh: the source simplified to `faces` triangles and tetrahedralized, with the study's
// placement data in mesh.json; kept when an earlier run made it from the same source.
cluster::TaskReport make_mesh(const StudyDef& def, const fs::path& out, const MeshTask& t,
                              const SurfaceMesh& source) {
  const ParticleSource& p = def.particles[t.particle];
  const std::string tag = source_tag(def, p, t.particle);
  const std::string label = p.name + " " + std::to_string(t.faces);
  const fs::path dir = mesh_dir(out, p.name, t.faces);
  const double cpu0 = thread_and_children_cpu_seconds();
  try {
    const fs::path report = dir / "mesh.json";
    if (fs::exists(report)) {
      const io::Json j = io::read_json_file(report);
      if (j.value("study_source", "") == tag && j.contains("lowest_point")) {
        return {.skipped = true, .note = label + " (kept)"};
      }
    }
    const geometry::PreparedParticle prepared = particle_mesh(source, p.name, t.faces);
    fs::create_directories(dir);
    io::remove_earlier_output(report);
    geometry::write_surface_mesh(dir / "surface.off", prepared.surface);
    nlohmann::json j = geometry::mesh_report(prepared);
    j["study_source"] = tag;
    Eigen::Index lowest = 0;
    prepared.surface.vertices.row(2).minCoeff(&lowest);
    const Vec3 low = prepared.surface.vertices.col(lowest);
    j["centroid_height"] = prepared.props.centroid.z() - low.z();
    j["lowest_point"] = {low.x(), low.y(), low.z()};
    j["dt_estimate_fem"] = estimated_dt(prepared.tets, def, fdem::BodyKind::deformable,
                                        prepared.props.equivalent_radius);
    j["dt_estimate_rigid"] =
        estimated_dt(prepared.tets, def, fdem::BodyKind::rigid, prepared.props.equivalent_radius);
    j["mesh_cpu_seconds"] = thread_and_children_cpu_seconds() - cpu0;
    io::write_atomically(report, j.dump(1) + "\n");
    return {.note = label + " triangles"};
  } catch (const std::exception& e) {
    return {.failed = true, .note = label + " FAILED", .payload = e.what()};
  }
}

// The source reference's options from the study: the levels' numbers (SourceReferenceOptions)
// but the finest size's elements across the contact radius.
SourceReferenceOptions source_options(const StudyDef& def) {
  SourceReferenceOptions o;
  o.elements_across = def.source_reference.elements_across;
  return o;
}

// The source reference's surface of one patch: the plan (strike point, Hertz contact radius at
// peak, the levels' element sizes) and the contact-local surface, kept when an earlier run made
// them from the same source, impact and options. mesh.json: the plan, the surface's centroid
// height above the strike point, the triangles kept and the CPU.
cluster::TaskReport make_source_mesh(const StudyDef& def, const fs::path& out, const MeshTask& t,
                                     const SurfaceMesh& source) {
  const ParticleSource& p = def.particles[t.particle];
  const SourceReferenceOptions options = source_options(def);
  std::ostringstream tag;
  tag.precision(17);
  tag << source_tag(def, p, t.particle)
      << " source-reference patch=" << t.source_patch * options.patch
      << " far_faces=" << options.far_faces << " levels=" << options.levels
      << " elements_across=" << options.elements_across << " coarsest_within=min(contact_edge,a/"
      << kCoarsestAcross << ") thin_face=" << geometry::kContactLocalThinFace
      << " speed=" << def.speed << " material=" << material_json(def.material).dump();
  const std::string label = p.name + (t.source_patch == 1 ? " source" : " source-patch2");
  const fs::path dir = source_mesh_dir(out, p.name, t.source_patch);
  const double cpu0 = thread_and_children_cpu_seconds();
  try {
    const fs::path report = dir / "mesh.json";
    if (fs::exists(report) && io::read_json_file(report).value("study_source", "") == tag.str()) {
      return {.skipped = true, .note = label + " (kept)"};
    }
    const SourceReferencePlan plan =
        plan_source_reference(source, def.material, def.speed, options);
    const geometry::ContactLocalSurface local = geometry::contact_local_surface(
        source, {.centre = plan.strike_point,
                 .radius = t.source_patch * options.patch * plan.equivalent_radius,
                 .far_faces = options.far_faces});
    fs::create_directories(dir);
    io::remove_earlier_output(report);
    geometry::write_surface_mesh(dir / "surface.off", local.surface);
    const Vec3& f = plan.strike_point;
    const OJson j = {
        {"study_source", tag.str()},
        {"patch_rel", t.source_patch * options.patch},
        {"source_faces", local.source_faces},
        {"kept_faces", local.kept_faces},
        {"faces", local.surface.faces.cols()},
        {"strike_point", {f.x(), f.y(), f.z()}},
        {"centroid_height", geometry::mass_properties(local.surface).centroid.z() - f.z()},
        {"equivalent_radius", plan.equivalent_radius},
        {"mass", plan.mass},
        {"local_radius", plan.local_radius},
        {"contact_radius", plan.contact_radius},
        {"hertz_peak_force", plan.peak_force},
        {"contact_edge", plan.contact_edge},
        {"element_sizes", plan.sizes},
        {"mesh_cpu_seconds", thread_and_children_cpu_seconds() - cpu0}};
    io::write_atomically(report, j.dump(1) + "\n");
    return {.note = label + " surface"};
  } catch (const std::exception& e) {
    return {.failed = true, .note = label + " FAILED", .payload = e.what()};
  }
}

// Phase 2, meshes: every particle at every resolution, over every rank's threads.
Meshes mesh_particles(const StudyDef& def, const fs::path& out,
                      const std::vector<std::size_t>& particles,
                      const std::vector<SurfaceMesh>& sources, int jobs, cluster::World& world,
                      bool quiet, const StopAt& stop_at, StudyOutcome& outcome) {
  Meshes m;
  // The sphere alone needs only the reference mesh (its volume).
  const bool polyhedra =
      std::any_of(def.models.begin(), def.models.end(), [](ModelKind k) { return !is_sphere(k); });
  for (std::size_t i : particles) {
    for (long n : def.resolutions) {
      if (polyhedra || n == def.reference) m.tasks.push_back({i, n});
    }
    if (def.reference_kind == ReferenceKind::source) {
      for (int patch = 1; patch <= (def.source_reference.patch_check ? 2 : 1); ++patch)
        m.tasks.push_back({i, 0, patch});
    }
  }
  const int n = static_cast<int>(m.tasks.size());
  // The finest meshes first: TetGen's cost grows with the triangle count.
  std::vector<int> order(m.tasks.size());
  for (int k = 0; k < n; ++k) order[static_cast<std::size_t>(k)] = k;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return m.tasks[static_cast<std::size_t>(a)].faces > m.tasks[static_cast<std::size_t>(b)].faces;
  });
  Progress progress(quiet || !world.root(), "meshes", n, n, world.size() > 1);
  const std::vector<cluster::TaskReport> reports = cluster::run_tasks(
      world, n, order, jobs,
      [&](int k) {
        const MeshTask& t = m.tasks[static_cast<std::size_t>(k)];
        if (past(stop_at)) {
          return cluster::TaskReport{.postponed = true,
                                     .note = def.particles[t.particle].name + " (postponed)"};
        }
        return t.source_patch > 0 ? make_source_mesh(def, out, t, sources[t.particle])
                                  : make_mesh(def, out, t, sources[t.particle]);
      },
      [&](const cluster::TaskReport& r, int running) { progress.done(r, 1, running); });
  for (const cluster::TaskReport& r : reports) {
    m.errors.push_back(r.failed ? r.payload : "");
    m.postponed += r.postponed ? 1 : 0;
    outcome.cpu_seconds += r.cpu_seconds;
  }
  return m;
}

// Phase 3, plans (every rank, from the meshes' mesh.json): per particle, the placement heights,
// the steps and the duration every case of it runs.
std::map<std::string, ParticlePlan> plan_particles(const StudyDef& def, const fs::path& out,
                                                   const Meshes& meshes,
                                                   const std::vector<CaseKey>& cases) {
  std::map<std::string, ParticlePlan> plans;
  const double e_star = effective_young(def.material, def.block_material);
  for (std::size_t k = 0; k < meshes.tasks.size(); ++k) {
    const MeshTask& t = meshes.tasks[k];
    ParticlePlan& pp = plans[def.particles[t.particle].name];
    if (!meshes.errors[k].empty()) {
      // The source reference's surface failing fails its cases alone.
      (t.source_patch > 0 ? pp.source_error : pp.mesh_error) =
          (t.source_patch > 0 ? std::string("the source reference's surface")
                              : std::to_string(t.faces) + " triangles") +
          ": " + meshes.errors[k];
      continue;
    }
    if (t.source_patch > 0) {
      const io::Json j = io::read_json_file(
          source_mesh_dir(out, def.particles[t.particle].name, t.source_patch) / "mesh.json");
      ParticlePlan::Source& src = pp.source[t.source_patch];
      const io::Json& f = j.at("strike_point");
      src.strike_point = Vec3(f[0].get<double>(), f[1].get<double>(), f[2].get<double>());
      src.centroid_height = j.at("centroid_height").get<double>();
      src.radius = j.at("equivalent_radius").get<double>();
      src.sizes = j.at("element_sizes").get<std::vector<double>>();
      continue;
    }
    const io::Json j =
        io::read_json_file(mesh_dir(out, def.particles[t.particle].name, t.faces) / "mesh.json");
    pp.centroid_height[t.faces] = j.at("centroid_height").get<double>();
    const io::Json& low = j.at("lowest_point");
    pp.lowest_point[t.faces] =
        Vec3(low[0].get<double>(), low[1].get<double>(), low[2].get<double>());
    pp.dt_fem[t.faces] = j.at("dt_estimate_fem").get<double>();
    pp.dt_rigid[t.faces] = j.at("dt_estimate_rigid").get<double>();
    if (t.faces == def.reference) {
      pp.radius = j.at("equivalent_radius").get<double>();
      pp.mass = def.material.density * j.at("volume").get<double>();
      if (std::find(def.models.begin(), def.models.end(), ModelKind::sphere_local) !=
          def.models.end()) {
        const LocalRadii r =
            local_radii(mesh_dir(out, def.particles[t.particle].name, t.faces) / "surface.off");
        pp.local_radius = r.equivalent, pp.local_r1 = r.r1, pp.local_r2 = r.r2;
      }
    }
  }
  for (auto& [name, pp] : plans) {
    if (!pp.mesh_error.empty()) continue;
    // "auto": the latest first contact of any of the particle's cases (its largest starting gap
    // at the launch speed; gravity only shortens it) plus 1.5 Hertz contact times of the
    // equivalent sphere. The contacts measured in the pilot studies (ballast and rock, 100–1000
    // triangles, fem and rigid, 1–2 m/s) lasted 0.5–1.0 of that time (the potential law's
    // corner contacts are stiff); 1.5 leaves half as much again for the tails of coarse meshes
    // (docs/study.md). The window is the cost: every step before and after contact counts.
    // The particle on the rigid block: its own mass and radius are the pair's effective ones.
    pp.contact_time = contact::hertz_contact_time(pp.mass, pp.radius, e_star, def.speed);
    double max_gap = 0;
    for (const CaseKey& c : cases) {
      if (c.particle != name || (c.source_patch > 0 && !pp.source.contains(c.source_patch)))
        continue;
      max_gap = std::max(max_gap, start_height(def, pp, c).second);
    }
    pp.duration = def.duration ? *def.duration : max_gap / def.speed + 1.5 * pp.contact_time;
  }
  return plans;
}

// One case: its scene.json, the run's outputs, and case.json last (the done marker); kept when
// an earlier run finished the same scene; failed.json when it fails.
cluster::TaskReport run_case(const StudyDef& def, const fs::path& out, const ParticlePlan& pp,
                             const CaseKey& c, const StopAt& stop_at) {
  const fs::path dir = case_dir(out, c);
  const std::string label = c.particle + " " + c.dir_name();
  if (past(stop_at)) return {.postponed = true, .note = label + " (postponed)"};
  try {
    fs::create_directories(dir);
    if (!pp.mesh_error.empty()) throw std::runtime_error("meshing failed at " + pp.mesh_error);
    if (c.source_patch > 0 && !pp.source_error.empty())
      throw std::runtime_error("meshing failed at " + pp.source_error);
    if (c.model == ModelKind::sphere_local && !(pp.local_radius > 0)) {
      throw std::runtime_error(
          "the reference mesh is flat or concave at its lowest vertex: no "
          "local sphere");
    }
    const scene::SceneDef scene_def =
        c.source_patch > 0 ? source_case_scene(def, out, pp, c) : case_scene(def, out, pp, c);
    // The scene at the window doubled n times (kMaxWindowDoublings): the same scene, rows and
    // steps up to the first window's end.
    const auto scene_text_at = [&](int n) {
      scene::SceneDef s = scene_def;
      s.duration = std::ldexp(scene_def.duration, n);
      return scene::scene_json(s, dir).dump(1) + "\n";
    };
    int first = 0;
    if (fs::exists(dir / "case.json")) {
      const std::string stored = read_text(dir / "scene.json");
      for (int n = 0; n <= kMaxWindowDoublings; ++n) {
        if (stored != scene_text_at(n)) continue;
        if (!stored_contact_open_at_end(dir))
          return {.skipped = true, .note = label + " (done before)"};
        first = n + 1;  // an earlier build took its cut curve as done: go on from its window
        break;
      }
    }
    run::RunResult result;
    double cpu = 0;
    int doublings = first;
    for (;; ++doublings) {
      if (doublings > kMaxWindowDoublings) {
        throw std::runtime_error("the contact is still open at the end of the window, " +
                                 fmt(std::ldexp(scene_def.duration, kMaxWindowDoublings)) + " s" +
                                 " (the study's window doubled " +
                                 std::to_string(kMaxWindowDoublings) +
                                 " times): its peak, impulse and duration would be a cut curve's");
      }
      // Outputs of an earlier, different case go first: only this run's may sit beside the new
      // scene.json.
      for (const char* f : {"case.json", "failed.json", "summary.json", "force.csv", "energy.csv"})
        io::remove_earlier_output(dir / f);
      io::write_atomically(dir / "scene.json", scene_text_at(doublings));
      const scene::SceneDef scene = scene::load_scene(dir / "scene.json");
      const double cpu0 = thread_and_children_cpu_seconds(), kept0 = run::kept_mesh_cpu_seconds();
      result = run::run_scene(scene, run::RunOptions{.stop_at = stop_at});
      // The case's CPU on this worker thread with its TetGen children's, its meshing included even
      // where this process had made the mesh for an earlier case (the rigid and rigid-penalty cases
      // of one resolution share it): what the case costs alone, whichever ran first. A case whose
      // window was doubled costs its last run (the earlier ones are that run's first part).
      cpu = thread_and_children_cpu_seconds() - cpu0 + (run::kept_mesh_cpu_seconds() - kept0);
      if (!contact_open_at_end(result)) break;
    }
    thin_rows(result, def.rows);
    run::write_outputs(result, dir);
    // The study's own facts of the case (its CPU on this thread, where the run's cpu_seconds counts
    // the time loop only; the element size at the strike point, m, null for the coarse default:
    // the refinement's over the reference mesh's R, or the source reference's level over the
    // source's own R).
    double h = c.relative_size * pp.radius, h_rel = c.relative_size;
    if (c.source_patch > 0) {
      const ParticlePlan::Source& src = pp.source.at(c.source_patch);
      h = level_size(src.sizes, c.level);
      h_rel = h / src.radius;
    }
    OJson record = {
        {"particle", c.particle},
        {"model", model_name(c.model)},
        {"resolution", is_sphere(c.model) || c.source_patch > 0 ? OJson() : OJson(c.resolution)},
        {"placement", placement_name(c.placement)},
        {"element_size", c.level > 0 ? OJson(h) : OJson()},
        {"element_size_rel", c.level > 0 ? OJson(h_rel) : OJson()},
        {"status", result.status},
        {"start_gap", start_height(def, pp, c).second},
        {"duration", std::ldexp(scene_def.duration, doublings)},
        {"window_doublings", doublings},
        {"hertz_contact_time", pp.contact_time},
        {"local_radii",
         c.model == ModelKind::sphere_local ? OJson{pp.local_r1, pp.local_r2} : OJson()},
        {"cpu_seconds", cpu}};
    if (c.source_patch > 0) record["source_patch"] = c.source_patch;  // 1 the patch, 2 doubled
    io::write_atomically(dir / "case.json", record.dump(1) + "\n");
    char buf[64];
    std::snprintf(buf, sizeof buf, " %.2f s", cpu);
    return {.note = label + buf};
  } catch (const run::RunStopped&) {
    // Cut by the deadline: only its scene.json is written, so the next run runs it again.
    return {.postponed = true, .note = label + " (stopped: postponed)"};
  } catch (const std::exception& e) {
    try {
      io::write_atomically(
          dir / "failed.json",
          OJson{{"particle", c.particle}, {"case", c.dir_name()}, {"message", e.what()}}.dump(1) +
              "\n");
    } catch (const std::exception&) {
      // The folder itself cannot be written: the report still counts the failure.
    }
    return {.failed = true, .note = label + " FAILED", .payload = e.what()};
  }
}

// Phase 4, cases: the most expensive first, over every rank's threads. Adds to `outcome` and
// `pool` (run_study runs a second round for the source reference's finer levels).
void run_cases(const StudyDef& def, const fs::path& out,
               const std::map<std::string, ParticlePlan>& plans, const std::vector<CaseKey>& cases,
               int jobs, cluster::World& world, bool quiet, const StopAt& stop_at,
               StudyOutcome& outcome, cluster::PoolStats& pool) {
  std::vector<int> order(cases.size());
  for (std::size_t k = 0; k < cases.size(); ++k) order[k] = static_cast<int>(k);
  const auto weight = [&](int k) { return case_weight(cases[static_cast<std::size_t>(k)]); };
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return weight(a) > weight(b); });
  double total_weight = 0;
  for (const CaseKey& c : cases) total_weight += case_weight(c);
  const int n = static_cast<int>(cases.size());
  outcome.cases += n;
  Progress progress(quiet || !world.root(), "cases", n, total_weight, world.size() > 1);
  cluster::PoolStats stats;
  const std::vector<cluster::TaskReport> reports = cluster::run_tasks(
      world, n, order, jobs,
      [&](int k) {
        const CaseKey& c = cases[static_cast<std::size_t>(k)];
        return run_case(def, out, plans.at(c.particle), c, stop_at);
      },
      [&](const cluster::TaskReport& r, int running) { progress.done(r, weight(r.task), running); },
      &stats);
  for (const cluster::TaskReport& r : reports) {
    outcome.failed += r.failed ? 1 : 0;
    outcome.skipped += r.skipped ? 1 : 0;
    outcome.postponed += r.postponed ? 1 : 0;
    outcome.ran += !r.failed && !r.skipped && !r.postponed ? 1 : 0;
    outcome.cpu_seconds += r.cpu_seconds;
  }
  // The rounds' pools as one: idle = 1 − Σ busy / (workers × Σ wall).
  pool.workers = std::max(pool.workers, stats.workers);
  pool.wall_seconds += stats.wall_seconds;
  pool.busy_seconds += stats.busy_seconds;
  pool.drain_seconds += stats.drain_seconds;
  pool.idle_fraction = pool.workers > 0 && pool.wall_seconds > 0
                           ? 1 - pool.busy_seconds / (pool.workers * pool.wall_seconds)
                           : 0;
  outcome.workers = pool.workers;
  outcome.idle_fraction = pool.idle_fraction;
  outcome.drain_seconds = pool.drain_seconds;
}

// The shard's cases of `plan`, in its order.
std::vector<CaseKey> of_shard(const StudyDef& def, const std::vector<std::size_t>& particles,
                              const std::vector<CaseKey>& plan) {
  std::vector<CaseKey> out;
  for (const CaseKey& c : plan) {
    for (std::size_t i : particles) {
      if (def.particles[i].name == c.particle) out.push_back(c);
    }
  }
  return out;
}

// The tag of round 2's list (cluster/task_pool.cpp uses 11-13 and 1000 up, world.cpp 7).
constexpr int kFinerLevelsTag = 21;

// Round 2: the source reference's finer levels that the levels just run ask for
// (plan_source_cases with OUT) and that were not among `ran`. Rank 0 reads the folder and sends
// every other rank the list (as indices into every level up to reference_max_levels), so that
// all ranks run the same cases whatever their view of the shared file system.
std::vector<CaseKey> finer_levels(const StudyDef& def, const fs::path& out,
                                  const std::vector<std::size_t>& particles,
                                  const std::vector<CaseKey>& ran, cluster::World& world) {
  const std::vector<CaseKey> candidates =
      of_shard(def, particles, source_cases(def, [&](const std::string&, Placement) {
                 return def.source_reference.max_levels;
               }));
  const auto id = [](const CaseKey& c) { return c.particle + "/" + c.dir_name(); };
  std::string text;
  if (world.root()) {
    std::set<std::string> done, wanted;
    for (const CaseKey& c : ran) done.insert(id(c));
    for (const CaseKey& c : of_shard(def, particles, plan_source_cases(def, out)))
      wanted.insert(id(c));
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      if (wanted.contains(id(candidates[k])) && !done.contains(id(candidates[k])))
        text += std::to_string(k) + " ";
    }
    for (int r = 1; r < world.size(); ++r) world.send(r, kFinerLevelsTag, text);
  } else {
    text = world.receive(0, kFinerLevelsTag);
  }
  std::vector<CaseKey> finer;
  std::istringstream in(text);
  for (std::size_t k; in >> k;) finer.push_back(candidates.at(k));
  return finer;
}

}  // namespace

StopAt deadline_after(double minutes) {
  if (!(minutes > 0)) return std::nullopt;
  return std::chrono::steady_clock::now() +
         std::chrono::duration_cast<std::chrono::steady_clock::duration>(
             std::chrono::duration<double>(60 * minutes));
}

StudyOutcome run_study(const StudyDef& def, const fs::path& out, const StudyRunOptions& options) {
  const auto wall0 = std::chrono::steady_clock::now();
  std::optional<cluster::World> own_world;
  cluster::World& world = options.world ? *options.world : own_world.emplace();
  const int jobs = thread_count(def, options);
  const std::vector<std::size_t> particles = shard_particles(def, options.shard);
  const std::vector<SurfaceMesh> sources = make_sources(def, particles);
  check_before_run(def, particles, sources);
  std::optional<FolderLock> lock;
  world.on_root([&] {
    fs::create_directories(out);
    lock.emplace(out, options.shard);
    adopt_folder(def, out);
    write_sources(def, out, particles, sources);
  });
  StudyOutcome outcome;
  outcome.ranks = world.size();
  const Meshes meshes = mesh_particles(def, out, particles, sources, jobs, world, options.quiet,
                                       options.stop_at, outcome);
  // Round 1: the study's cases and the source reference's levels that its folder already asks for
  // (plan_source_cases with OUT: the first three, and a fourth where an earlier run's three
  // finished and want it).
  std::vector<CaseKey> cases = of_shard(def, particles, plan_cases(def));
  for (const CaseKey& c : of_shard(def, particles, plan_source_cases(def, out))) cases.push_back(c);
  if (meshes.postponed > 0) {
    // The deadline passed while meshing: the cases cannot be planned without every mesh, so
    // all of them wait for the next run.
    outcome.cases = outcome.postponed = static_cast<int>(cases.size());
  } else {
    const std::map<std::string, ParticlePlan> plans = plan_particles(def, out, meshes, cases);
    cluster::PoolStats pool;
    run_cases(def, out, plans, cases, jobs, world, options.quiet, options.stop_at, outcome, pool);
    // Round 2: the fourth levels that round 1's levels ask for (wants_finer_level), on the
    // same plans: a level starts where the others of its patch do, so the particle's duration
    // (its largest start gap) is unchanged. Every rank runs it (finer_levels), and a shard its
    // own particles': `--collect` refuses while one is unfinished (unfinished_cases).
    if (def.reference_kind == ReferenceKind::source) {
      const std::vector<CaseKey> finer = finer_levels(def, out, particles, cases, world);
      if (!finer.empty())
        run_cases(def, out, plans, finer, jobs, world, options.quiet, options.stop_at, outcome,
                  pool);
    }
  }
  outcome.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return outcome;
}

}  // namespace asperity::study
