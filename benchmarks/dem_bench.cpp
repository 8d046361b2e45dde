// Throughput of the sphere DEM step: steps/s for one Hertz pair, contact updates/s for a packing.
#include <cmath>
#include <numbers>

#include <benchmark/benchmark.h>

#include "solver/dem/sphere_world.hpp"

namespace {

using namespace asperity;

dem::SphereWorld make_world(int n, double radius, bool hertz_mindlin) {
  dem::SphereWorld w;
  w.materials = {{.name = "glass",
                  .density = 2500,
                  .young = 6.3e10,
                  .poisson = 0.23,
                  .friction = 0.3,
                  .restitution = 0.8}};
  w.law.normal = contact::NormalLaw::hertz;
  w.law.tangential = hertz_mindlin;
  const double m = 2500 * 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
  w.radius.assign(n, radius);
  w.mass.assign(n, m);
  w.inertia.assign(n, 0.4 * m * radius * radius);
  w.material.assign(n, 0);
  w.body.resize(n);
  for (int i = 0; i < n; ++i) w.body[i] = i;
  w.fixed.assign(n, 0);
  w.x = Eigen::Matrix3Xd::Zero(3, n);
  w.v = Eigen::Matrix3Xd::Zero(3, n);
  w.w = Eigen::Matrix3Xd::Zero(3, n);
  return w;
}

// One sphere bouncing on a plane: the per-step overhead of the whole loop.
void BM_HertzPair100kSteps(benchmark::State& state) {
  for (auto _ : state) {
    state.PauseTiming();
    dem::SphereWorld w = make_world(1, 0.01, true);
    w.x.col(0) = Vec3(0, 0, 0.01 + 1e-7);
    w.v.col(0) = Vec3(0.1, 0, -1);
    w.walls.push_back({.kind = dem::WallKind::plane,
                       .a = Vec3::Zero(),
                       .b = Vec3::UnitZ(),
                       .material = 0,
                       .body = 1});
    dem::initialise(w);
    state.ResumeTiming();
    for (int k = 0; k < 100'000; ++k) dem::step(w, 5e-9);  // 0.5 ms: the contact lasts ~60 µs
    benchmark::DoNotOptimize(w.x.data());
  }
  state.counters["steps/s"] = benchmark::Counter(1e5 * static_cast<double>(state.iterations()),
                                                 benchmark::Counter::kIsRate);
}
BENCHMARK(BM_HertzPair100kSteps)->Unit(benchmark::kMillisecond);

// 10,000 spheres on a simple-cubic lattice, each pressed 0.1 % into its six neighbours, resting
// on a plane under gravity: ~30,000 persistent contacts from the first step.
void BM_Packing10k(benchmark::State& state) {
  const int side_x = 25, side_y = 20, side_z = 20;
  const double r = 0.001, spacing = 2 * r * (1 - 1e-3);
  dem::SphereWorld w = make_world(side_x * side_y * side_z, r, state.range(0) != 0);
  int i = 0;
  for (int z = 0; z < side_z; ++z)
    for (int y = 0; y < side_y; ++y)
      for (int x = 0; x < side_x; ++x)
        w.x.col(i++) = Vec3(x * spacing, y * spacing, r * (1 - 1e-3) + z * spacing);
  w.walls.push_back({.kind = dem::WallKind::plane,
                     .a = Vec3::Zero(),
                     .b = Vec3::UnitZ(),
                     .material = 0,
                     .body = side_x * side_y * side_z});  // the body after the spheres
  w.gravity = Vec3(0, 0, -9.81);
  dem::initialise(w);
  const long updates0 = w.contact_updates;
  long steps = 0;
  for (auto _ : state) {
    for (int k = 0; k < 20; ++k) dem::step(w, 1e-8);
    steps += 20;
  }
  state.counters["steps/s"] =
      benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate);
  state.counters["contacts/s"] = benchmark::Counter(
      static_cast<double>(w.contact_updates - updates0), benchmark::Counter::kIsRate);
  state.counters["contacts"] =
      static_cast<double>(w.contact_updates - updates0) / static_cast<double>(steps);
}
BENCHMARK(BM_Packing10k)->Arg(0)->Arg(1)->ArgName("mindlin")->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
