// Geometry pipeline benchmarks: edge-collapse simplification 60,500 → 1000 triangles and TetGen
// tetrahedralization of the result (issue 3, "Performance"); one core (the code is serial).
#include <benchmark/benchmark.h>

#include "solver/geometry/random_particle.hpp"
#include "solver/geometry/simplify_edge_collapse.hpp"
#include "solver/geometry/tet_quality.hpp"
#include "solver/geometry/tetrahedralize.hpp"

namespace {
using namespace asperity;

// 20 n² faces with n = 55: 60,500 triangles, the size of a fine scan.
const SurfaceMesh& fine_particle() {
  static const SurfaceMesh p = geometry::random_particle({.seed = 2024, .faces = 60000});
  return p;
}

void BM_Simplify60kTo1000(benchmark::State& state) {
  const SurfaceMesh& p = fine_particle();
  for (auto _ : state) benchmark::DoNotOptimize(geometry::simplify_edge_collapse(p, 1000));
  state.counters["input_faces"] = static_cast<double>(p.faces.cols());
  state.counters["faces_per_s"] = benchmark::Counter(static_cast<double>(p.faces.cols() - 1000),
                                                     benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_Simplify60kTo1000)->Unit(benchmark::kMillisecond);

void BM_Tetrahedralize1000(benchmark::State& state) {
  const SurfaceMesh s = geometry::simplify_edge_collapse(fine_particle(), 1000);
  long tets = 0;
  for (auto _ : state) {
    const TetMesh t = geometry::tetrahedralize(s);
    tets = static_cast<long>(t.tets.cols());
    benchmark::DoNotOptimize(t.tets.data());
  }
  state.counters["tets"] = static_cast<double>(tets);
}
BENCHMARK(BM_Tetrahedralize1000)->Unit(benchmark::kMillisecond);

// The target, measured as one: 60k → 1000 triangles → tetrahedra.
void BM_Simplify60kAndTetrahedralize(benchmark::State& state) {
  const SurfaceMesh& p = fine_particle();
  for (auto _ : state) {
    const TetMesh t = geometry::tetrahedralize(geometry::simplify_edge_collapse(p, 1000));
    benchmark::DoNotOptimize(t.tets.data());
  }
}
BENCHMARK(BM_Simplify60kAndTetrahedralize)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
