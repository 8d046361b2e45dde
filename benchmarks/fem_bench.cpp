// FEM/DEM benchmarks: the two kernels that take the time, and whole collisions by resolution.
#include <benchmark/benchmark.h>

#include <ctime>

#include "contact/munjiza_potential.hpp"
#include "fdem_scenes.hpp"
#include "fem/tet_elements.hpp"
#if ASPERITY_HAVE_GEOMETRY
#include "geometry/mesh_pipeline.hpp"
#include "geometry/random_particle.hpp"
#endif

namespace asperity {
namespace {

// Internal forces of a ball of 6 n³ tetrahedra, slightly deformed (every element takes the full
// path: log, cofactor, scatter). Counter: tetrahedron updates per second on one core.
void BM_InternalForces(benchmark::State& state) {
  const TetMesh m = fdem::ball_mesh(0.1, static_cast<int>(state.range(0)));
  const fem::TetElements e = fem::make_tet_elements(m.nodes, m.tets, 1e9, 0.3, 2000, 0, "ball");
  Eigen::Matrix3Xd x = m.nodes;
  x.row(0) *= 1.01;
  const Eigen::Matrix3Xd v = Eigen::Matrix3Xd::Zero(3, x.cols());
  Eigen::Matrix3Xd f(3, x.cols());
  for (auto _ : state) {
    f.setZero();
    const auto r = fem::add_internal_forces(e, x, v, f, false);
    benchmark::DoNotOptimize(r);
    benchmark::DoNotOptimize(f.data());
  }
  state.counters["tets"] = e.size();
  state.counters["tet_updates/s"] = benchmark::Counter(
      static_cast<double>(e.size()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_InternalForces)->Arg(8)->Arg(16)->Arg(24);

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
// A generated rock-like particle (5 cm, 50 GPa, ρ = 2650) simplified to N surface triangles,
// tetrahedralized, deformable, striking a fixed block at 1 m/s from 0.2 mm above it; one run to
// the end of the first contact at dt = 0.5 × the predicted critical step. CPU seconds per
// collision are the time; the profile counters say where it goes.
void BM_Collision(benchmark::State& state) {
  const long faces = state.range(0);
  geometry::ParticleDef pd{.seed = 3, .size = 0.05, .faces = 20 * 9 * 9};
  geometry::PipelineOptions o;
  o.faces = faces;
  const TetMesh mesh = geometry::prepare_particle(geometry::random_particle(pd), "rock", o).tets;
  const Material rock{.name = "rock", .density = 2650, .young = 5e10, .poisson = 0.25};
  for (auto _ : state) {
    fdem::WorldDef def;
    TetMesh m = mesh;
    m.nodes.row(2).array() += 0.0002 - m.nodes.row(2).minCoeff();
    def.bodies.push_back({.name = "rock",
                          .kind = fdem::BodyKind::deformable,
                          .mesh = m,
                          .material = rock,
                          .velocity = Vec3(0, 0, -1)});
    def.bodies.push_back(
        {.name = "block",
         .kind = fdem::BodyKind::fixed,
         .mesh = fdem::box_mesh(Vec3(-0.1, -0.1, -0.05), Vec3(0.1, 0.1, 0), 1, 1, 1),
         .material = rock});
    fdem::World w = fdem::make_world(def);
    const std::clock_t c0 = std::clock();
    const fdem::scenes::Impact im = fdem::scenes::run_impact(w, 0.01);
    const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    state.SetIterationTime(cpu);
    state.counters["tets"] = w.elements[0].size();
    state.counters["surface_tets"] = static_cast<double>(w.surface_tets.cols());
    state.counters["steps"] = static_cast<double>(im.steps);
    state.counters["dt"] = im.dt;
    state.counters["peak_N"] = im.peak_force;
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
BENCHMARK(BM_Collision)
    ->Arg(100)
    ->Arg(250)
    ->Arg(500)
    ->Arg(1000)
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);
#endif

}  // namespace
}  // namespace asperity

BENCHMARK_MAIN();
