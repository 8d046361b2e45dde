// Throughput of the sphere DEM step: steps/s for one Hertz pair, contact updates/s for a packing;
// and a whole run of a large bed, its set-up against its steps and its memory per sphere.
#include <cmath>
#include <numbers>
#include <string>

#include <benchmark/benchmark.h>

#include "scenes/dem_scenes.hpp"
#include "solver/core/clock.hpp"
#include "solver/dem/mindlin_columns.hpp"
#include "solver/dem/sphere_world.hpp"
#include "solver/run/run_scene.hpp"

namespace {

using namespace asperity;

dem::SphereWorld make_world(int n, double radius, bool hertz_mindlin) {
  dem::SphereWorld w;
  w.materials = {test::glass(0.3, 0.8)};
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

// The Hertz–Mindlin law over one batch of 32 touching contacts in columns
// (dem/mindlin_columns.hpp), in the copy named by the argument: 0 the baseline's, 1 x86-64-v3's
// (AVX2), 2 x86-64-v4's (AVX-512); skipped where this CPU cannot run it. A copy's share of
// BM_Packing10k's contact pass, apart from the gather and the sums: the force loop runs only the
// widest copy the CPU has, so this is where the others are measured. The contacts: the packing's
// lattice contacts (glass, r = 1 mm, pressed 0.1 %), with slips and springs that stick.
void BM_MindlinColumns(benchmark::State& state) {
  const auto copy = static_cast<dem::MindlinCopy>(state.range(0));
  const dem::MindlinColumnsFn law = dem::mindlin_columns_copy(copy);
  if (law == nullptr) {
    state.SkipWithError("this CPU does not run that copy");
    return;
  }
  const contact::HertzMindlinCoefficients c =
      contact::hertz_mindlin_coefficients({.young_eff = 3.3e10,
                                           .shear_eff = 1.4e10,
                                           .radius_eff = 5e-4,
                                           .mass_eff = 5.2e-6,
                                           .zeta = 0.2,
                                           .friction = 0.3});
  dem::MindlinColumns b{};
  double history[4][dem::kColumn] = {};
  const std::size_t t = dem::kBatch;
  for (std::size_t m = 0; m < t; ++m) {
    const double s = 1e-3 * static_cast<double>(m);
    b.d[0][m] = 2e-3 * (1 - 1e-3);
    b.d[1][m] = 1e-6 * s;
    b.d[2][m] = -1e-6 * s;
    b.dist[m] = std::sqrt(b.d[0][m] * b.d[0][m] + b.d[1][m] * b.d[1][m] + b.d[2][m] * b.d[2][m]);
    b.overlap[m] = 2e-3 - b.dist[m];
    b.ri[m] = b.rj[m] = 1e-3;
    for (int a = 0; a < 3; ++a) {
      b.vi[a][m] = 1e-4 * (a + 1) * s;
      b.vj[a][m] = -1e-4 * s;
      b.wi[a][m] = 0.1 * s;
      b.wj[a][m] = -0.1 * (a - 1) * s;
      b.dv_end[a][m] = 2e-4 * s;
    }
    b.k[m] = c.normal.k;
    b.damping[m] = c.normal.damping;
    b.shear[m] = c.shear;
    b.shear_damping[m] = c.shear_damping;
    b.friction[m] = c.friction;
    b.inv_min_radius[m] = 1e3;
  }
  long contacts = 0;
  for (auto _ : state) {
    for (int k = 0; k < 1000; ++k) {
      law(b, t, 1e-8, history[0], history[1], history[2], history[3]);
      benchmark::ClobberMemory();
    }
    contacts += 1000 * static_cast<long>(t);
  }
  state.counters["contacts/s"] =
      benchmark::Counter(static_cast<double>(contacts), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_MindlinColumns)->Arg(0)->Arg(1)->Arg(2)->ArgName("copy");

// A whole `asperity run` of the bed of tools/cases/bed_scene.py at N spheres (a cube of side
// ∛N on the plane, glass, Hertz–Mindlin, dt 2.5e-7 s, 20 steps), built in memory instead of read
// from a scene file (a million spheres is 177 MB of JSON, over the loader's 64 MiB,
// docs/hostile.md): the set-up (the world, its starting-overlap check on the cell grid, the
// critical step) against the steps, and the solver state per sphere (summary.json `state_bytes`,
// the scene definition apart).
void BM_BedRun(benchmark::State& state) {
  const int side = static_cast<int>(std::lround(std::cbrt(static_cast<double>(state.range(0)))));
  const double r = 1e-3, spacing = 2 * r * (1 + 1e-9), dt = 2.5e-7;
  scene::SceneDef s;
  s.name = "bed";
  s.duration = 20 * dt;
  s.dt = dt;
  s.gravity = Vec3(0, 0, -9.81);
  s.materials = {test::glass(0.3, 0.8)};
  for (int z = 0; z < side; ++z)
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) {
        std::string name = "s";
        name += std::to_string(s.bodies.size());
        s.bodies.push_back(
            {.name = name,
             .material = 0,
             .shape = scene::SphereShape{.radius = r},
             .position = Vec3(x * spacing, y * spacing, r * (1 + 1e-9) + z * spacing)});
      }
  s.bodies.push_back({.name = "floor",
                      .material = 0,
                      .shape = scene::PlaneShape{.point = Vec3::Zero(), .normal = Vec3::UnitZ()},
                      .fixed = true});
  s.contact.law = scene::ContactLaw::hertz_mindlin;
  s.record = {.body = static_cast<int>(s.bodies.size()) - 1, .every = 20};
  double setup = 0, steps = 0, bytes = 0;
  for (auto _ : state) {
    const double cpu0 = thread_cpu_seconds();
    const run::RunResult result = run::run_scene(s, {.keep_rows = false});
    const double total = thread_cpu_seconds() - cpu0;
    steps = result.summary["cpu_seconds"].get<double>();
    setup = total - steps;
    bytes = result.summary["state_bytes"].get<double>();
  }
  const double n = static_cast<double>(side) * side * side;
  state.counters["spheres"] = n;
  state.counters["setup_s"] = setup;
  state.counters["setup_per_sphere_us"] = 1e6 * setup / n;
  state.counters["step_per_sphere_ns"] = 1e9 * steps / 20 / n;
  state.counters["state_bytes_per_sphere"] = bytes / n;
}
BENCHMARK(BM_BedRun)->Arg(100'000)->Arg(1'000'000)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
