// FEM/DEM benchmarks: the two kernels that take the time, and whole collisions by resolution.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <ctime>

#include "scenes/fdem_scenes.hpp"
#include "solver/contact/munjiza_potential.hpp"
#include "solver/fdem/time_step.hpp"
#include "solver/fem/tet_elements.hpp"
#if ASPERITY_HAVE_GEOMETRY
#include "solver/geometry/mesh_pipeline.hpp"
#include "solver/geometry/random_particle.hpp"
#include "solver/io/json_file.hpp"
#endif

#include <string>

namespace asperity {
namespace {

// The internal-force benchmarks' body: a ball of 6 n³ tetrahedra stretched 1 % along x, so that
// every element takes the full path (log, cofactor, scatter).
struct StretchedBall {
  fem::TetElements e;
  Eigen::Matrix3Xd x;
};
StretchedBall stretched_ball(int n) {
  const TetMesh m = fdem::ball_mesh(0.1, n);
  StretchedBall b{.e = fem::make_tet_elements(m.nodes, m.tets, 1e9, 0.3, 2000, 0, "ball"),
                  .x = m.nodes};
  b.x.row(0) *= 1.01;
  return b;
}

// Their counters: the elements, and tetrahedron updates per second on one core.
void count_tet_updates(benchmark::State& state, const fem::TetElements& e) {
  state.counters["tets"] = e.size();
  state.counters["tet_updates/s"] = benchmark::Counter(
      static_cast<double>(e.size()), benchmark::Counter::kIsIterationInvariantRate);
}

// Internal forces of the stretched ball through the batched element loop.
void BM_InternalForces(benchmark::State& state) {
  const auto [e, x] = stretched_ball(static_cast<int>(state.range(0)));
  const Eigen::Matrix3Xd v = Eigen::Matrix3Xd::Zero(3, x.cols());
  Eigen::Matrix3Xd f(3, x.cols());
  for (auto _ : state) {
    f.setZero();
    const auto r = fem::add_internal_forces(e, x, v, f, false);
    benchmark::DoNotOptimize(r);
    benchmark::DoNotOptimize(f.data());
  }
  count_tet_updates(state, e);
}
BENCHMARK(BM_InternalForces)->Arg(8)->Arg(16)->Arg(24);

// The same forces element by element through the one-element kernel (fem/neo_hookean_tet.hpp):
// the element loop as it was before the batched one (fem/internal_forces.cpp), whose result it
// equals to round-off (to the bit without FMA); kept as the before of that change, in the same
// process.
void BM_InternalForcesPerElement(benchmark::State& state) {
  const auto [e, x] = stretched_ball(static_cast<int>(state.range(0)));
  Eigen::Matrix3Xd f(3, x.cols());
  for (auto _ : state) {
    f.setZero();
    double energy = 0;
    for (int k = 0; k < e.size(); ++k) {
      double* p[4];
      for (int a = 0; a < 4; ++a) p[a] = f.data() + 3 * e.tets(a, k);
      fem::neo_hookean_tet_forces<false>(
          &e.dm_inv[9 * static_cast<std::size_t>(k)], e.volume[k], e.lame,
          x.data() + 3 * e.tets(0, k), x.data() + 3 * e.tets(1, k), x.data() + 3 * e.tets(2, k),
          x.data() + 3 * e.tets(3, k), p[0], p[1], p[2], p[3], &energy);
    }
    benchmark::DoNotOptimize(f.data());
  }
  count_tet_updates(state, e);
}
BENCHMARK(BM_InternalForcesPerElement)->Arg(8)->Arg(16)->Arg(24);

// One overlapping pair of tetrahedra through the Munjiza kernel (both passes: 32 face ×
// sub-tetrahedron clips). Counter: pair evaluations per second.
void BM_ContactKernel(benchmark::State& state) {
  const contact::TetNodes b = {Vec3(0, 0, 0), Vec3(1.1, 0.1, -0.05), Vec3(0.2, 0.9, 0.1),
                               Vec3(0.1, 0.15, 1.05)};
  const Mat3 r = Eigen::AngleAxisd(0.4, Vec3(0.3, -1, 0.5).normalized()).toRotationMatrix();
  contact::TetNodes a = {Vec3(0, 0, 0), Vec3(0.9, 0, 0), Vec3(0.1, 0.8, 0), Vec3(0.2, 0.1, 0.95)};
  for (Vec3& x : a) x = r * x + Vec3(0.15, 0.1, 0.2);
  const bool with_energy = state.range(0) != 0;
  for (auto _ : state) {
    const auto c = contact::munjiza_potential(a, b, 1e9, with_energy);
    benchmark::DoNotOptimize(c);
  }
  state.counters["pairs/s"] = benchmark::Counter(1, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ContactKernel)->Arg(0)->Arg(1);

#if ASPERITY_HAVE_GEOMETRY
const Material kRock{.name = "rock", .density = 2650, .young = 5e10, .poisson = 0.25};

// Coulomb friction of both bodies of the collisions (--friction=MU; 0 by default, as the set's
// survey in reports/fem/collision_cost.md ran).
double g_friction = 0;

// The contact's share of the step the collisions run with: 0, α = 10 as the WorldDef gives it;
// 2, what a scene that leaves the penalty to the solver gets (contact.max_contact_factor 2 met by
// face-penalty, run/run_fdem.cpp). Set by --scene-default.
double g_contact_factor = 0;

// The bench_fem collision's world: a tetrahedral particle, deformable, 0.2 mm above a fixed block,
// falling at 1 m/s; the contact as g_contact_factor says.
fdem::WorldDef collision_def(const TetMesh& mesh) {
  fdem::WorldDef def;
  TetMesh m = mesh;
  m.nodes.row(2).array() += 0.0002 - m.nodes.row(2).minCoeff();
  Material rock = kRock;
  rock.friction = g_friction;
  def.bodies.push_back({.name = "rock",
                        .kind = fdem::BodyKind::deformable,
                        .mesh = m,
                        .material = rock,
                        .velocity = Vec3(0, 0, -1)});
  def.bodies.push_back({.name = "block",
                        .kind = fdem::BodyKind::fixed,
                        .mesh = fdem::box_mesh(Vec3(-0.1, -0.1, -0.05), Vec3(0.1, 0.1, 0), 1, 1, 1),
                        .material = rock});
  def.contact.max_contact_factor = g_contact_factor;
  def.contact.contact_step_fix = fdem::ContactStepFix::face_penalty;
  return def;
}

// The bench_fem collision: one run to the end of the first contact at dt = 0.5 × the predicted
// critical step. CPU seconds of the run per collision are the time (the world's set-up and
// critical step apart: setup_cpu_s); the profile counters say where it goes.
void run_collision(benchmark::State& state, const TetMesh& mesh) {
  for (auto _ : state) {
    const fdem::WorldDef def = collision_def(mesh);
    const std::clock_t s0 = std::clock();
    fdem::World w = fdem::make_world(def);
    const fdem::CriticalStep step = fdem::critical_step(w);
    const std::clock_t c0 = std::clock();
    const fdem::scenes::Impact im = fdem::scenes::run_impact(w, 0.01);
    const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    state.SetIterationTime(cpu);
    state.counters["setup_cpu_s"] = static_cast<double>(c0 - s0) / CLOCKS_PER_SEC;
    state.counters["contact_factor_limit"] = g_contact_factor;
    state.counters["penalty_scale_min"] =
        w.tet_penalty_scale.empty()
            ? 1.0
            : *std::min_element(w.tet_penalty_scale.begin(), w.tet_penalty_scale.end());
    state.counters["tets"] = w.elements[0].size();
    state.counters["surface_tets"] = static_cast<double>(w.surface_tets.cols());
    state.counters["steps"] = static_cast<double>(im.steps);
    state.counters["dt"] = im.dt;
    state.counters["dt_element"] = step.element;
    state.counters["dt_contact"] = step.contact;
    state.counters["peak_N"] = im.peak_force;
    // What a change of the kernels must leave alone (to round-off): the rebound, the energy
    // drift and the final energies.
    const EnergyBalance e = fdem::energy(w);
    state.counters["v_after"] = im.v_after.z();
    state.counters["drift"] = im.drift;
    state.counters["E_kinetic"] = e.kinetic;
    state.counters["E_elastic"] = e.elastic;
    // Candidate pairs per step: whose boxes overlap (through the kernel), and touching.
    const double steps = static_cast<double>(w.steps);
    state.counters["pairs_kernel"] = static_cast<double>(w.contact_evaluations) / steps;
    state.counters["pairs_touching"] = static_cast<double>(w.contacts_touching) / steps;
    state.counters["pairs_listed"] = static_cast<double>(w.pairs.size());
    state.counters["cpu_s"] = cpu;
    // Shares of the profiled phase time (ticks, core/profile.hpp).
    const Profile& p = w.profile;
    const double all = static_cast<double>(p.total());
    state.counters["frac_internal"] = static_cast<double>(p.internal) / all;
    state.counters["frac_contact"] = static_cast<double>(p.contact) / all;
    state.counters["frac_broad"] = static_cast<double>(p.broad_phase) / all;
    state.counters["frac_integrate"] = static_cast<double>(p.integrate) / all;
  }
}

// The benchmark's own particle (seed 3, 5 cm) simplified to N surface triangles.
void BM_Collision(benchmark::State& state) {
  const long faces = state.range(0);
  geometry::ParticleDef pd{.seed = 3, .size = 0.05, .faces = 20 * 9 * 9};
  geometry::PipelineOptions o;
  o.faces = faces;
  run_collision(state, geometry::prepare_particle(geometry::random_particle(pd), "rock", o).tets);
}
BENCHMARK(BM_Collision)
    ->Arg(100)
    ->Arg(250)
    ->Arg(500)
    ->Arg(1000)
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);

// The same collision for each particle of the generated set (data/particles/set.json: shape,
// seed and source resolution as the set gives them, the size the benchmark's 5 cm), at N surface
// triangles (100, 250, 500, 1000): the cost over 50 shapes, not one seed (issue 11, item 6).
// Registered by main for the particles --set-particles=K names (the first K; default 2, the
// smoke test's).
void BM_CollisionSet(benchmark::State& state, geometry::ParticleDef pd, long faces) {
  pd.size = 0.05;
  geometry::PipelineOptions o;
  o.faces = faces;
  run_collision(state, geometry::prepare_particle(geometry::random_particle(pd), "rock", o).tets);
}

// The set-up alone of the collision's world at the scene default (make_world with
// contact.max_contact_factor 2 by face-penalty, whose fdem::limit_face_penalty evaluates the
// element step bound several times, then the critical step), for the particles of the set at 1000
// surface triangles, meshed once outside the timing (issue 11: the default's set-up cost).
void BM_CollisionSetup(benchmark::State& state, geometry::ParticleDef pd) {
  pd.size = 0.05;
  geometry::PipelineOptions o;
  o.faces = 1000;
  const TetMesh mesh = geometry::prepare_particle(geometry::random_particle(pd), "rock", o).tets;
  const double kept = g_contact_factor;
  g_contact_factor = 2;
  fdem::WorldDef def = collision_def(mesh);
  g_contact_factor = kept;
  for (auto _ : state) {
    fdem::World w = fdem::make_world(def);
    const fdem::CriticalStep step = fdem::critical_step(w);
    benchmark::DoNotOptimize(step);
    state.counters["dt"] = step.critical;
    state.counters["penalty_scale_min"] =
        w.tet_penalty_scale.empty()
            ? 1.0
            : *std::min_element(w.tet_penalty_scale.begin(), w.tet_penalty_scale.end());
  }
  state.counters["tets"] = static_cast<double>(mesh.tets.cols());
}

void register_set(int count, const std::string& file) {
  const io::Json set = io::read_json_file(file);
  const io::JsonReader list = io::JsonReader(set, file, "").child("particles");
  for (std::size_t k = 0, n = list.require_array(); k < n && static_cast<int>(k) < count; ++k) {
    const io::JsonReader p = list.at(k);
    const geometry::ParticleDef pd = geometry::read_particle_def(p);
    for (const long faces : {100L, 250L, 500L, 1000L}) {
      const std::string name = "BM_CollisionSet/" + p.string("name") + "/" + std::to_string(faces);
      benchmark::RegisterBenchmark(name.c_str(), BM_CollisionSet, pd, faces)
          ->Iterations(1)
          ->UseManualTime()
          ->Unit(benchmark::kSecond);
    }
    benchmark::RegisterBenchmark(("BM_CollisionSetup/" + p.string("name") + "/1000").c_str(),
                                 BM_CollisionSetup, pd)
        ->Iterations(3)
        ->Unit(benchmark::kMillisecond)
        ->MeasureProcessCPUTime();
  }
}
#endif

}  // namespace
}  // namespace asperity

// Google Benchmark's main, plus --set-particles=K (BM_CollisionSet and BM_CollisionSetup over the
// first K particles of the set; default 2, "all" for every one), --set-file=PATH (another particle
// set, e.g. seeds outside the study's; default data/particles/set.json), --friction=MU (both
// bodies' Coulomb coefficient; default 0) and --scene-default (the collisions at the scene
// default's contact.max_contact_factor 2 by face-penalty instead of α = 10 as the WorldDef gives
// it).
int main(int argc, char** argv) {
#if ASPERITY_HAVE_GEOMETRY
  int count = 2;
  std::string set_file = std::string(ASPERITY_SOURCE_DIR) + "/data/particles/set.json";
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.rfind("--set-particles=", 0) == 0) {
      const std::string v = a.substr(16);
      count = v == "all" ? 1 << 30 : std::stoi(v);
    } else if (a.rfind("--set-file=", 0) == 0) {
      set_file = a.substr(11);
    } else if (a.rfind("--friction=", 0) == 0) {
      asperity::g_friction = std::stod(a.substr(11));
    } else if (a == "--scene-default") {
      asperity::g_contact_factor = 2;
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  asperity::register_set(count, set_file);
#endif
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
