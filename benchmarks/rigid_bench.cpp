// Rigid polyhedra under the volume laws: the overlap kernel, the narrow phase and whole drops by
// resolution. Asserts nothing; the numbers go to docs/physics.md and reports/rigid/.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <ctime>
#include <string>
#include <vector>

#include "scenes/volume_scenes.hpp"
#include "solver/contact/overlap_volume.hpp"
#include "solver/fdem/broad_phase.hpp"
#include "solver/geometry/mesh_pipeline.hpp"
#include "solver/geometry/random_particle.hpp"

namespace asperity {
namespace {

// One triangle clipped by one tetrahedron it crosses (4 clips, 5-vertex result). Counter:
// clips per second.
void BM_OverlapKernel(benchmark::State& state) {
  const contact::TetNodes t = {Vec3(0, 0, 0), Vec3(1.1, 0.1, -0.05), Vec3(0.2, 0.9, 0.1),
                               Vec3(0.1, 0.15, 1.05)};
  const contact::Triangle tri = {Vec3(-0.2, 0.1, 0.2), Vec3(0.8, 0.2, 0.1), Vec3(0.2, 0.9, 0.3)};
  for (auto _ : state) {
    contact::OverlapSide s;
    benchmark::DoNotOptimize(contact::clip_triangle_in_tet(tri, t, Vec3::Zero(), s));
    benchmark::DoNotOptimize(s);
  }
  state.counters["clips/s"] = benchmark::Counter(1, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_OverlapKernel);

// The study's rock (seed 3, 5 cm, granite) at N surface triangles, through the pipeline.
TetMesh rock(long faces) {
  geometry::ParticleDef pd{.seed = 3, .size = 0.05, .faces = 20 * 12 * 12};  // 2,880 triangles
  geometry::PipelineOptions o;
  o.faces = faces;
  return geometry::prepare_particle(geometry::random_particle(pd), "rock", o).tets;
}

const Material kGranite{.name = "granite", .density = 2650, .young = 5e10, .poisson = 0.25};

fdem::WorldDef rock_on_block(const TetMesh& mesh, double depth, double speed) {
  fdem::WorldDef def;
  TetMesh m = mesh;
  m.nodes.row(2).array() -= m.nodes.row(2).minCoeff() + depth;
  def.bodies.push_back({.name = "rock",
                        .kind = fdem::BodyKind::rigid,
                        .mesh = m,
                        .material = kGranite,
                        .velocity = Vec3(0, 0, -speed)});
  def.bodies.push_back(fdem::volume_scenes::block(0.05, kGranite));
  def.contact.law = fdem::ContactLaw::volume_hertz;
  return def;
}

// The narrow phase of one step with the rock pressed 0.5 mm (1 % of its size) into the block,
// at rest: every candidate pair clipped, forces assembled. Counters: candidate pairs and the time
// per pair, which stays flat with N when nothing grows as N².
void BM_NarrowPhase(benchmark::State& state) {
  fdem::World w = fdem::make_world(rock_on_block(rock(state.range(0)), 5e-4, 0));
  long evaluations = 0;
  for (auto _ : state) {
    const long before = w.contact_evaluations;
    fdem::step(w, 0.0);
    evaluations = w.contact_evaluations - before;
  }
  state.counters["candidate_pairs"] = static_cast<double>(w.pairs.size());
  state.counters["overlapping_boxes"] = static_cast<double>(evaluations);
  state.counters["pairs/s"] = benchmark::Counter(static_cast<double>(w.pairs.size()),
                                                 benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_NarrowPhase)->Arg(100)->Arg(250)->Arg(500)->Arg(1000)->Arg(2000);

// The broad phase of the YADE cross-check's convex hulls (data/meshes/convex/hull-seed3-N.off,
// N = 50–2000 vertices, 96–3,996 triangles, tetrahedralized as a scene loads them: TetGen keeping
// the facets, no interior points, so the tetrahedra are long and nearly every pair of them
// overlaps along any axis) pressed 0.5 mm into the block: one candidate_pairs call. Counters:
// tetrahedra, candidate pairs, and the time per tetrahedron, flat when the cost is O(n log n + k).
void BM_BroadPhaseHull(benchmark::State& state) {
  const std::string file = std::string(ASPERITY_SOURCE_DIR) + "/data/meshes/convex/hull-seed3-" +
                           std::to_string(state.range(0)) + ".off";
  geometry::PipelineOptions o;
  o.tetrahedralize = true;
  fdem::World w =
      fdem::make_world(rock_on_block(geometry::prepare_particle(file, o).tets, 5e-4, 0));
  std::vector<std::uint8_t> fixed(w.bodies.size());
  for (std::size_t b = 0; b < w.bodies.size(); ++b) {
    fixed[b] = w.bodies[b].kind == fdem::BodyKind::fixed;
  }
  std::size_t pairs = 0;
  for (auto _ : state) {
    const auto p = fdem::candidate_pairs(w.x, w.surface_tets, w.surface_tet_body, fixed, w.skin);
    pairs = p.size();
    benchmark::DoNotOptimize(p.data());
  }
  state.counters["tets"] = static_cast<double>(w.surface_tets.cols());
  state.counters["candidate_pairs"] = static_cast<double>(pairs);
  state.counters["tets/s"] = benchmark::Counter(static_cast<double>(w.surface_tets.cols()),
                                                benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_BroadPhaseHull)
    ->Arg(50)
    ->Arg(250)
    ->Arg(1000)
    ->Arg(2000)
    ->Unit(benchmark::kMillisecond);

// A whole drop: the rock at 1 m/s from 0.2 mm above the block to the end of its contact, at the
// default step (0.01 of the predicted one). CPU seconds per impact; the phases' shares.
void BM_RigidDrop(benchmark::State& state) {
  const TetMesh mesh = rock(state.range(0));
  for (auto _ : state) {
    fdem::World w = fdem::make_world(rock_on_block(mesh, -2e-4, 1.0));
    const std::clock_t c0 = std::clock();
    const auto im = fdem::volume_scenes::run_impact(w, 0.01);
    const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    state.SetIterationTime(cpu);
    state.counters["steps"] = static_cast<double>(im.steps);
    state.counters["peak_N"] = im.peak_force;
    state.counters["cpu_s"] = cpu;
    // Shares of the profiled phase time (ticks).
    const double all = static_cast<double>(std::max<std::uint64_t>(1, w.profile.total()));
    state.counters["frac_contact"] = static_cast<double>(w.profile.contact) / all;
    state.counters["frac_broad"] = static_cast<double>(w.profile.broad_phase) / all;
    state.counters["tets"] = static_cast<double>(w.surface_tets.cols());
  }
}
BENCHMARK(BM_RigidDrop)
    ->Arg(100)
    ->Arg(250)
    ->Arg(500)
    ->Arg(1000)
    ->Arg(2000)
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);

}  // namespace
}  // namespace asperity

BENCHMARK_MAIN();
