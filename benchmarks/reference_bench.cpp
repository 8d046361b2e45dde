// Cost of the finite-sphere reference (validation/reference/finite_sphere.hpp): fitting the law
// F/F_Hertz(s) at mesh level M (what the first finite_sphere_impact call per ν pays, at M = 16),
// and one impact from the cached law (every later call). Counters: elements, nodes.
#include <benchmark/benchmark.h>

#include "validation/reference/finite_sphere.hpp"

namespace asperity::reference {
namespace {

void BM_FiniteSphereLaw(benchmark::State& state) {
  const int M = static_cast<int>(state.range(0));
  for (auto _ : state) {
    const FiniteSphereLaw law = fit_finite_sphere_law(0.3, {.angular_cells = M});
    benchmark::DoNotOptimize(law.coefficients.data());
  }
  const FiniteSphere sphere({.youngs_modulus = 1.0, .poisson_ratio = 0.3, .radius = 1.0},
                            {.angular_cells = M});
  state.counters["elements"] = sphere.elements();
  state.counters["nodes"] = sphere.nodes();
}
BENCHMARK(BM_FiniteSphereLaw)->Arg(8)->Arg(16)->Unit(benchmark::kMillisecond);

void BM_FiniteSphereImpactCached(benchmark::State& state) {
  finite_sphere_impact(10e6, 0.3, 1000.0, 0.1, 0.2);  // fits and caches the ν = 0.3 law
  double v = 0.2;
  for (auto _ : state) {
    benchmark::DoNotOptimize(finite_sphere_impact(10e6, 0.3, 1000.0, 0.1, v));
    v = v < 0.4 ? v * 1.001 : 0.2;
  }
}
BENCHMARK(BM_FiniteSphereImpactCached)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace asperity::reference

BENCHMARK_MAIN();
