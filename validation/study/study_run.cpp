// The study runner: sources → meshes → cases, each phase in a pool of worker threads.
#include "study/study_run.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <numbers>
#include <sstream>
#include <thread>

#include "core/clock.hpp"
#include "core/error.hpp"
#include "fdem/fdem_world.hpp"
#include "fdem/structured_mesh.hpp"
#include "fdem/time_step.hpp"
#include "geometry/mesh_pipeline.hpp"
#include "geometry/random_particle.hpp"
#include "geometry/splitmix64.hpp"
#include "geometry/write_mesh.hpp"
#include "io/atomic_file.hpp"
#include "io/json_file.hpp"
#include "run/run_scene.hpp"
#include "scene/scene.hpp"

namespace asperity::study {
namespace fs = std::filesystem;
using OJson = nlohmann::ordered_json;

namespace {

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return {};
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

Mat3 orientation_matrix(const StudyDef& def, std::size_t index) {
  if (def.random_orientation) {
    // Uniform random rotation (Shoemake 1992, "Uniform random rotations", Graphics Gems III):
    // a unit quaternion from three uniforms; seeded by the particle's place in the study.
    geometry::SplitMix64 rng{0x5eedULL + 7919ULL * index};
    const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
    const double a = std::sqrt(1 - u1), b = std::sqrt(u1), tau = 2 * std::numbers::pi;
    const Quat q(b * std::cos(tau * u3), a * std::sin(tau * u2), a * std::cos(tau * u2),
                 b * std::sin(tau * u3));
    return q.normalized().toRotationMatrix();
  }
  const Vec3 r = def.orientation_deg * (std::numbers::pi / 180);
  return (Eigen::AngleAxisd(r.z(), Vec3::UnitZ()) * Eigen::AngleAxisd(r.y(), Vec3::UnitY()) *
          Eigen::AngleAxisd(r.x(), Vec3::UnitX()))
      .toRotationMatrix();
}

// What makes a particle's source surface: the meshes of an earlier run are reused only when it
// matches.
std::string source_tag(const StudyDef& def, const ParticleSource& p, std::size_t index) {
  std::ostringstream s;
  s.precision(17);
  if (p.file.empty()) {
    s << "generated seed=" << p.seed << " size=" << p.size << " elongation=" << p.elongation
      << " flatness=" << p.flatness << " angularity=" << p.angularity
      << " roughness=" << p.roughness << " faces=" << p.faces;
  } else {
    s << "file=" << fs::absolute(p.file).string() << " scale=" << p.scale
      << " mtime=" << fs::last_write_time(p.file).time_since_epoch().count();
  }
  s << " particle_size=" << (def.particle_size ? *def.particle_size : 0.0);
  if (def.random_orientation) {
    s << " orientation=random#" << index;
  } else {
    s << " orientation=" << def.orientation_deg.x() << "," << def.orientation_deg.y() << ","
      << def.orientation_deg.z();
  }
  return s.str();
}

// The particle's source surface: centroid at the origin, scaled to particle_size (when given),
// rotated to the study's orientation.
SurfaceMesh make_source(const StudyDef& def, const ParticleSource& p, std::size_t index) {
  SurfaceMesh m;
  if (p.file.empty()) {
    geometry::ParticleDef d{.seed = p.seed,
                            .size = p.size,
                            .elongation = p.elongation,
                            .flatness = p.flatness,
                            .angularity = p.angularity,
                            .roughness = p.roughness,
                            .faces = p.faces};
    if (const std::string problem = geometry::particle_def_problem(d); !problem.empty()) {
      throw InputError(def.file.string() + ": particles: \"" + p.name + "\": " + problem);
    }
    m = geometry::random_particle(d);
  } else {
    geometry::PipelineOptions o;
    o.read.scale = p.scale;
    o.tetrahedralize = false;
    m = geometry::prepare_particle(p.file, o).surface;
  }
  const geometry::MassProperties props = geometry::mass_properties(m);
  const double s = def.particle_size ? *def.particle_size / (2 * props.equivalent_radius) : 1.0;
  const Mat3 rot = orientation_matrix(def, index);
  for (Eigen::Index i = 0; i < m.vertices.cols(); ++i) {
    m.vertices.col(i) = rot * (s * (m.vertices.col(i) - props.centroid));
  }
  return m;
}

// Runs tasks 0..n-1 on `jobs` threads; `run(k)` must not throw.
void parallel_for(int n, int jobs, const std::function<void(int)>& run) {
  std::atomic<int> next{0};
  auto worker = [&] {
    for (int k = next++; k < n; k = next++) run(k);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::min(jobs, n); ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
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

// Progress on stderr: a line redrawn in place on a terminal, else one line every 10 s.
class Progress {
 public:
  Progress(bool quiet, std::string what, int total, double total_weight)
      : quiet_(quiet),
        tty_(isatty(2) != 0),
        what_(std::move(what)),
        total_(total),
        total_weight_(total_weight) {}
  // `kept`: done by an earlier run; it leaves the time-left estimate (its weight took no time).
  void done(double weight, const std::string& last, bool failed, bool kept = false) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++count_;
    failed_ += failed ? 1 : 0;
    (kept ? total_weight_ -= weight : weight_ += weight);
    if (quiet_) return;
    const double el = elapsed();
    if (!tty_ && el - last_print_ < 10 && count_ < total_) return;
    last_print_ = el;
    const double left = weight_ > 0 ? el * (total_weight_ - weight_) / weight_ : 0;
    std::fprintf(stderr, "%s%s [%d/%d]%s  %s elapsed, ~%s left  (%s)%s", tty_ ? "\r\033[K" : "",
                 what_.c_str(), count_, total_,
                 failed_ > 0 ? (" " + std::to_string(failed_) + " failed").c_str() : "",
                 clock_text(el).c_str(), clock_text(left).c_str(), last.c_str(), tty_ ? "" : "\n");
    if (tty_ && count_ == total_) std::fprintf(stderr, "\n");
  }
  double elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  bool quiet_, tty_;
  std::string what_;
  int total_;
  double total_weight_;
  std::mutex mutex_;
  int count_ = 0, failed_ = 0;
  double weight_ = 0, last_print_ = -1e9;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// Relative cost of a case for scheduling (longest first) and the time-left estimate: the FEM/DEM
// collision costs about N^1.4 (measured, docs/study.md); a rigid polyhedron has no element
// forces; the sphere is a few thousand DEM steps.
double case_weight(const CaseKey& c) {
  const double n = std::pow(static_cast<double>(c.resolution) / 100.0, 1.4);
  switch (c.model) {
    case ModelKind::fem:
      return n;
    case ModelKind::rigid:
      return 0.5 * n;
    case ModelKind::sphere:
      return 0.01;
  }
  return 1;
}

OJson material_json(const Material& m) {
  return {
      {"density", m.density}, {"young", m.young}, {"poisson", m.poisson}, {"friction", m.friction}};
}

fs::path mesh_dir(const fs::path& out, const std::string& particle, long faces) {
  return out / "meshes" / particle / std::to_string(faces);
}

// Per particle, from its meshes: where each case starts and how long every case runs.
struct ParticlePlan {
  std::map<long, double> centroid_height;   // centroid above the lowest vertex, per resolution, m
  std::map<long, double> dt_fem, dt_rigid;  // estimated steps (for the rows kept), s
  double radius = 0, mass = 0;              // volume-equivalent sphere of the reference mesh
  double duration = 0, contact_time = 0;    // s
  std::string mesh_error;                   // non-empty: a resolution failed to mesh
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
  const double ref = def.gap + reach;
  if (c.model == ModelKind::sphere) {
    const double z = c.placement == Placement::centroid ? std::max(ref, def.gap + pp.radius)
                                                        : def.gap + pp.radius;
    return {z, z - pp.radius};
  }
  const double h = pp.centroid_height.at(c.resolution);
  const double z = c.placement == Placement::centroid ? ref : def.gap + h;
  return {z, z - h};
}

OJson case_scene(const StudyDef& def, const ParticlePlan& pp, const CaseKey& c) {
  const auto [z, gap] = start_height(def, pp, c);
  (void)gap;
  const double half = 2 * pp.radius + 0.01,
               depth = 2 * pp.radius + 0.01;  // block: wider than the particle
  OJson particle = {{"name", "particle"}, {"material", "particle"}};
  long every = 1;
  if (c.model == ModelKind::sphere) {
    particle["shape"] = {{"type", "sphere"}, {"radius", pp.radius}};
  } else {
    const fs::path rel = fs::path("..") / ".." / ".." / "meshes" / c.particle /
                         std::to_string(c.resolution) / "surface.off";
    particle["shape"] = {{"type", "mesh"}, {"file", rel.generic_string()}};
    particle["model"] = model_name(c.model);
    const double dt = (c.model == ModelKind::fem ? pp.dt_fem : pp.dt_rigid).at(c.resolution);
    every = std::max(1L, static_cast<long>(pp.duration / dt / def.rows));
  }
  particle["position"] = {0.0, 0.0, z};
  particle["velocity"] = {0.0, 0.0, -def.speed};
  OJson scene = {
      {"name", c.particle + "-" + c.dir_name()},
      {"gravity", {0.0, 0.0, -def.gravity}},
      {"duration", pp.duration},
      {"dt", "auto"},
      {"materials",
       {{"particle", material_json(def.material)}, {"block", material_json(def.block_material)}}},
      {"bodies",
       {particle,
        {{"name", "block"},
         {"material", "block"},
         {"shape",
          {{"type", "box"}, {"min", {-half, -half, -depth}}, {"max", {half, half, 0.0}}}}}}},
      {"contact", {{"law", c.model == ModelKind::sphere ? "hertz" : "potential"}}},
      {"record", {{"force_on", "particle"}, {"every", every}}}};
  if (def.penalty_alpha && c.model != ModelKind::sphere) {
    scene["contact"]["penalty_alpha"] = *def.penalty_alpha;
  }
  if (def.end_after_separation && c.model != ModelKind::sphere) {
    scene["record"]["end_after_separation"] = *def.end_after_separation * pp.contact_time;
  }
  return scene;
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
// default safety (run/step_policy.hpp): only used to keep about `rows` rows per case.
double estimated_dt(const TetMesh& tets, const StudyDef& def, fdem::BodyKind kind, double radius) {
  fdem::WorldDef w;
  TetMesh m = tets;
  m.nodes.row(2).array() += def.gap - m.nodes.row(2).minCoeff();
  w.bodies.push_back({.name = "particle",
                      .kind = kind,
                      .mesh = m,
                      .material = def.material,
                      .velocity = Vec3(0, 0, -def.speed)});
  const double half = 2 * radius + 0.01;
  w.bodies.push_back(
      {.name = "block",
       .kind = fdem::BodyKind::fixed,
       .mesh = fdem::box_mesh(Vec3(-half, -half, -half), Vec3(half, half, 0), 1, 1, 1),
       .material = def.block_material});
  if (def.penalty_alpha) w.contact.alpha = *def.penalty_alpha;
  const fdem::World world = fdem::make_world(w);
  return run::default_safety(kind == fdem::BodyKind::rigid ? run::StepRegime::fdem_rigid
                                                           : run::StepRegime::fdem_deformable) *
         fdem::critical_step(world).critical;
}

}  // namespace

std::string CaseKey::dir_name() const {
  if (model == ModelKind::sphere) return std::string("sphere-") + placement_name(placement);
  return std::string(model_name(model)) + "-" + std::to_string(resolution) + "-" +
         placement_name(placement);
}

double hertz_contact_time(double radius, double mass, double effective_young, double speed) {
  return 2.868 * std::pow(mass * mass / (radius * effective_young * effective_young * speed), 0.2);
}

std::vector<CaseKey> plan_cases(const StudyDef& def) {
  std::vector<CaseKey> out;
  for (const ParticleSource& p : def.particles) {
    for (ModelKind m : def.models) {
      if (m == ModelKind::sphere) {
        for (Placement pl : def.placements) out.push_back({p.name, m, 0, pl});
        continue;
      }
      for (long n : def.resolutions) {
        for (Placement pl : def.placements) out.push_back({p.name, m, n, pl});
      }
    }
  }
  return out;
}

StudyOutcome run_study(const StudyDef& def, const fs::path& out, const StudyRunOptions& options) {
  const auto wall0 = std::chrono::steady_clock::now();
  const int jobs = options.jobs > 0 ? options.jobs
                   : def.jobs > 0
                       ? def.jobs
                       : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  StudyOutcome outcome;
  std::mutex mutex;
  fs::create_directories(out);
  // One study at a time per folder: a second one would write the same cases.
  const int lock_fd = ::open((out / "study.lock").c_str(), O_CREAT | O_RDWR, 0644);
  if (lock_fd < 0 || ::flock(lock_fd, LOCK_EX | LOCK_NB) != 0) {
    throw InputError(out.string() + ": another asperity study is running in this folder");
  }
  struct Unlock {
    int fd;
    ~Unlock() { ::close(fd); }
  } unlock{lock_fd};

  // 1. Sources (cheap, serial): each particle's surface, written for the record.
  const std::size_t np = def.particles.size();
  std::vector<SurfaceMesh> sources(np);
  std::vector<std::string> tags(np);
  for (std::size_t i = 0; i < np; ++i) {
    sources[i] = make_source(def, def.particles[i], i);
    tags[i] = source_tag(def, def.particles[i], i);
    const fs::path f = out / "particles" / (def.particles[i].name + ".off");
    fs::create_directories(f.parent_path());
    geometry::write_surface_mesh(f, sources[i]);
  }

  // 2. Meshes: every particle at every resolution (skipped when an earlier run made the same).
  struct MeshTask {
    std::size_t particle;
    long faces;
  };
  std::vector<MeshTask> mesh_tasks;
  // The sphere alone needs only the reference mesh (its volume).
  const bool polyhedra = std::any_of(def.models.begin(), def.models.end(),
                                     [](ModelKind m) { return m != ModelKind::sphere; });
  for (std::size_t i = 0; i < np; ++i) {
    for (long n : def.resolutions) {
      if (polyhedra || n == def.reference) mesh_tasks.push_back({i, n});
    }
  }
  std::vector<std::string> mesh_errors(mesh_tasks.size());
  {
    Progress progress(options.quiet, "meshes", static_cast<int>(mesh_tasks.size()),
                      static_cast<double>(mesh_tasks.size()));
    parallel_for(static_cast<int>(mesh_tasks.size()), jobs, [&](int k) {
      const MeshTask& t = mesh_tasks[k];
      const ParticleSource& p = def.particles[t.particle];
      const fs::path dir = mesh_dir(out, p.name, t.faces);
      const double cpu0 = thread_cpu_seconds();
      try {
        const fs::path report = dir / "mesh.json";
        if (fs::exists(report)) {
          const io::Json j = io::read_json_file(report);
          if (j.value("study_source", "") == tags[t.particle] && j.contains("dt_estimate_rigid")) {
            progress.done(1, p.name + " " + std::to_string(t.faces) + " (kept)", false, true);
            return;
          }
        }
        geometry::PipelineOptions o;
        o.faces = t.faces;
        o.tetrahedralize = true;
        const geometry::PreparedParticle prepared =
            geometry::prepare_particle(sources[t.particle], p.name, o);
        fs::create_directories(dir);
        fs::remove(report);
        geometry::write_surface_mesh(dir / "surface.off", prepared.surface);
        nlohmann::json j = geometry::mesh_report(prepared);
        j["study_source"] = tags[t.particle];
        j["centroid_height"] =
            prepared.props.centroid.z() - prepared.surface.vertices.row(2).minCoeff();
        j["dt_estimate_fem"] = estimated_dt(prepared.tets, def, fdem::BodyKind::deformable,
                                            prepared.props.equivalent_radius);
        j["dt_estimate_rigid"] = estimated_dt(prepared.tets, def, fdem::BodyKind::rigid,
                                              prepared.props.equivalent_radius);
        j["mesh_cpu_seconds"] = thread_cpu_seconds() - cpu0;
        io::write_atomically(report, j.dump(1) + "\n");
        progress.done(1, p.name + " " + std::to_string(t.faces) + " triangles", false);
      } catch (const std::exception& e) {
        mesh_errors[k] = e.what();
        progress.done(1, p.name + " " + std::to_string(t.faces) + " FAILED", true);
      }
      std::lock_guard<std::mutex> lock(mutex);
      outcome.cpu_seconds += thread_cpu_seconds() - cpu0;
    });
  }

  // 3. Per particle: placement heights, steps and the duration every case of it runs.
  std::map<std::string, ParticlePlan> plans;
  const double e_star = effective_young(def.material, def.block_material);
  for (std::size_t k = 0; k < mesh_tasks.size(); ++k) {
    ParticlePlan& pp = plans[def.particles[mesh_tasks[k].particle].name];
    if (!mesh_errors[k].empty()) {
      pp.mesh_error = std::to_string(mesh_tasks[k].faces) + " triangles: " + mesh_errors[k];
      continue;
    }
    const io::Json j = io::read_json_file(
        mesh_dir(out, def.particles[mesh_tasks[k].particle].name, mesh_tasks[k].faces) /
        "mesh.json");
    pp.centroid_height[mesh_tasks[k].faces] = j.at("centroid_height").get<double>();
    pp.dt_fem[mesh_tasks[k].faces] = j.at("dt_estimate_fem").get<double>();
    pp.dt_rigid[mesh_tasks[k].faces] = j.at("dt_estimate_rigid").get<double>();
    if (mesh_tasks[k].faces == def.reference) {
      pp.radius = j.at("equivalent_radius").get<double>();
      pp.mass = def.material.density * j.at("volume").get<double>();
    }
  }
  const std::vector<CaseKey> cases = plan_cases(def);
  for (auto& [name, pp] : plans) {
    if (!pp.mesh_error.empty()) continue;
    // "auto": the latest first contact of any of the particle's cases (its largest starting gap
    // at the launch speed; gravity only shortens it) plus 1.5 Hertz contact times of the
    // equivalent sphere. The contacts measured in the pilot studies (ballast and rock, 100–1000
    // triangles, fem and rigid, 1–2 m/s) lasted 0.5–1.0 of that time (the potential law's
    // corner contacts are stiff); 1.5 leaves half as much again for the tails of coarse meshes
    // (docs/study.md). The window is the cost: every step before and after contact counts.
    pp.contact_time = hertz_contact_time(pp.radius, pp.mass, e_star, def.speed);
    double max_gap = 0;
    for (const CaseKey& c : cases) {
      if (c.particle == name) max_gap = std::max(max_gap, start_height(def, pp, c).second);
    }
    pp.duration = def.duration ? *def.duration : max_gap / def.speed + 1.5 * pp.contact_time;
  }

  // 4. Cases, longest first.
  std::vector<int> order(cases.size());
  for (std::size_t k = 0; k < cases.size(); ++k) order[k] = static_cast<int>(k);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return case_weight(cases[a]) > case_weight(cases[b]); });
  double total_weight = 0;
  for (const CaseKey& c : cases) total_weight += case_weight(c);
  outcome.cases = static_cast<int>(cases.size());
  Progress progress(options.quiet, "cases", outcome.cases, total_weight);
  parallel_for(static_cast<int>(order.size()), jobs, [&](int k) {
    const CaseKey& c = cases[order[k]];
    const ParticlePlan& pp = plans.at(c.particle);
    const fs::path dir = out / "cases" / c.particle / c.dir_name();
    const std::string label = c.particle + " " + c.dir_name();
    const double cpu0 = thread_cpu_seconds();
    bool failed = false, skipped = false;
    try {
      fs::create_directories(dir);
      if (!pp.mesh_error.empty()) throw std::runtime_error("meshing failed at " + pp.mesh_error);
      const std::string scene_text = case_scene(def, pp, c).dump(1) + "\n";
      if (fs::exists(dir / "case.json") && read_text(dir / "scene.json") == scene_text) {
        skipped = true;
      } else {
        // Outputs of an earlier, different case go first: only this run's may sit beside the
        // new scene.json.
        for (const char* f :
             {"case.json", "failed.json", "summary.json", "force.csv", "energy.csv"})
          fs::remove(dir / f);
        io::write_atomically(dir / "scene.json", scene_text);
        const scene::SceneDef scene = scene::load_scene(dir / "scene.json");
        const double run_cpu0 = thread_cpu_seconds();
        run::RunResult result = run::run_scene(scene, run::RunOptions{});
        const double cpu = thread_cpu_seconds() - run_cpu0;
        thin_rows(result, def.rows);
        // The case's CPU on this worker thread (the run's own cpu_seconds counts the time loop
        // only).
        result.summary["cpu_seconds_thread"] = cpu;
        run::write_outputs(result, dir);
        OJson record = {
            {"particle", c.particle},
            {"model", model_name(c.model)},
            {"resolution", c.model == ModelKind::sphere ? OJson() : OJson(c.resolution)},
            {"placement", placement_name(c.placement)},
            {"status", result.status},
            {"start_gap", start_height(def, pp, c).second},
            {"duration", pp.duration},
            {"hertz_contact_time", pp.contact_time},
            {"cpu_seconds", cpu}};
        io::write_atomically(dir / "case.json", record.dump(1) + "\n");
      }
    } catch (const std::exception& e) {
      failed = true;
      try {
        io::write_atomically(
            dir / "failed.json",
            OJson{{"particle", c.particle}, {"case", c.dir_name()}, {"message", e.what()}}.dump(1) +
                "\n");
      } catch (const std::exception&) {
        // The folder itself cannot be written: the count below still reports the failure.
      }
    }
    const double cpu = thread_cpu_seconds() - cpu0;
    {
      std::lock_guard<std::mutex> lock(mutex);
      outcome.failed += failed ? 1 : 0;
      outcome.skipped += skipped ? 1 : 0;
      outcome.ran += (!failed && !skipped) ? 1 : 0;
      outcome.cpu_seconds += cpu;
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, " %.2f s", cpu);
    progress.done(case_weight(c),
                  label + (failed    ? " FAILED"
                           : skipped ? " (done before)"
                                     : buf),
                  failed, skipped);
  });
  outcome.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return outcome;
}

}  // namespace asperity::study
