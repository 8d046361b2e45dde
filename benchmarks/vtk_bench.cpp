// Cost of ParaView frames (run/vtk_series.hpp) on a whole FEM/DEM collision through the runner:
// the generated rock of bench_fem's BM_Collision (5 cm, 50 GPa, seed 3) at 1000 surface
// triangles, deformable, striking a fixed block at 1 m/s, run to 20 µs after its contact ends,
// without frames (arg 0) and with a frame every N steps (arg N). Counters: CPU seconds of the
// run, frames, bytes per frame, and the share of the run's wall time spent writing frames.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <ctime>
#include <filesystem>
#include <fstream>

#include "solver/geometry/mass_properties.hpp"
#include "solver/geometry/random_particle.hpp"
#include "solver/geometry/write_mesh.hpp"
#include "solver/run/run_scene.hpp"
#include "solver/scene/scene.hpp"

namespace asperity {
namespace {

namespace fs = std::filesystem;

scene::SceneDef collision_scene(const fs::path& dir) {
  const geometry::ParticleDef pd{.seed = 3, .size = 0.05, .faces = 20 * 9 * 9};
  const SurfaceMesh surface = geometry::random_particle(pd);
  geometry::write_surface_mesh(dir / "rock.off", surface);
  // The run places the centroid at `position`: its lowest point 0.2 mm above the block (as
  // BM_Collision), measured on the unsimplified surface.
  const double below =
      geometry::mass_properties(surface).centroid.z() - surface.vertices.row(2).minCoeff();
  scene::SceneDef s;
  s.file = dir / "scene.json";
  s.name = "vtk-bench";
  s.duration = 0.01;
  const Material rock{.name = "rock", .density = 2650, .young = 5e10, .poisson = 0.25};
  s.materials = {rock};
  s.contact.law = scene::ContactLaw::potential;
  scene::BodyDef particle{.name = "rock",
                          .material = 0,
                          .shape = scene::MeshShape{.file = dir / "rock.off", .faces = 1000},
                          .model = scene::Model::fem,
                          .position = Vec3(0, 0, below + 0.0002),
                          .velocity = Vec3(0, 0, -1)};
  s.bodies.push_back(particle);
  s.bodies.push_back(
      {.name = "block",
       .material = 0,
       .shape = scene::BoxShape{.min = Vec3(-0.1, -0.1, -0.05), .max = Vec3(0.1, 0.1, 0)},
       .fixed = true});
  s.record = {.body = 0, .every = 100, .end_after_separation = 2e-5};
  return s;
}

void BM_CollisionFrames(benchmark::State& state) {
  const fs::path dir =
      fs::temp_directory_path() / ("asperity_bench_vtk_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  scene::SceneDef s = collision_scene(dir);
  for (auto _ : state) {
    run::RunOptions o{.keep_rows = false};
    if (state.range(0) > 0)
      o.vtk = run::VtkOutput{.dir = dir / "vtk", .every = static_cast<int>(state.range(0))};
    const std::clock_t c0 = std::clock();
    const run::RunResult r = run::run_scene(s, o);
    const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    state.SetIterationTime(cpu);
    state.counters["cpu_s"] = cpu;
    state.counters["steps"] = r.summary["steps"].get<double>();
    state.counters["frames"] = static_cast<double>(r.vtk.frames);
    state.counters["bytes_per_frame"] =
        r.vtk.frames > 0 ? static_cast<double>(r.vtk.bytes) / static_cast<double>(r.vtk.frames) : 0;
    state.counters["write_share"] = r.vtk.write_seconds / r.summary["wall_seconds"].get<double>();
    state.counters["peak_N"] = r.summary["peak_force"].get<double>();
  }
  fs::remove_all(dir);
}
BENCHMARK(BM_CollisionFrames)
    ->Arg(0)
    ->Arg(100)
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);

}  // namespace
}  // namespace asperity

BENCHMARK_MAIN();
