// CalculiX beside asperity on deformable impacts (issue 29): the CalculiX peer
// (peers/calculix.cpp) runs the sphere of scenes/hertz_spheres.hpp as a contract scene: one
// coarse level held against the dynamic finite-sphere reference (validation/reference/) in CI,
// and sequences of whole-field refinements whose Richardson limits are held against asperity's
// own (label calculix-full); and the same for particles (generated ones of
// data/particles/set.json and a scanned stone) striking a plane at their lowest vertex, both codes
// running the same scene file (label calculix-full).
//
// The peak both sides compare is the T/20-filtered peak (run/impact_measures.hpp): asperity's
// explicit step resolves the highest element modes, whose ringing its raw peak carries (0.3–0.9 %
// of Hertz at α = 10, more as the contact refines: docs/physics.md, "Ringing"); ccx's implicit
// step (T_H/100, HHT α = −0.05) cannot carry them, so its raw and filtered peaks differ by 0.1–0.3
// point. Filtered against filtered is the comparison that does not depend on the step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "peers/peer.hpp"
#include "scenes/hertz_series.hpp"
#include "solver/core/richardson.hpp"
#include "solver/geometry/mesh_pipeline.hpp"
#include "solver/geometry/random_particle.hpp"
#include "solver/geometry/write_mesh.hpp"
#include "solver/io/json_file.hpp"
#include "solver/run/run_scene.hpp"
#include "solver/scene/scene_json.hpp"
#include "validation/reference/finite_sphere_dynamic.hpp"

namespace asperity {
namespace {
namespace fs = std::filesystem;
using fdem::hertz::kRadius;

// One refinement level's measures, relative to Hertz at the level's own meshed mass.
struct Measured {
  double s = 0;
  double err_peak = 0, err_filtered = 0, err_duration = 0;
  double impulse_ratio = 0;  // ∫F dt / (2 m v)
  double cpu = 0;            // s
  long nodes = 0;
};

fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("asperity-calculix-" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// The Hertz sphere at contact size a/R and refinement s as a contract scene (the element-size
// keys of scenes/hertz_series.hpp's level_mesh), small-strain linear like the reference, and run
// through the CalculiX adapter.
Measured calculix_level(double a_over_r, double s, const std::string& tag) {
  Material m = fdem::scenes::rubbery();
  const double speed = fdem::hertz::speed_for(a_over_r, m);
  const double k = fdem::hertz::contact_scale(speed);
  const fs::path dir = scratch(tag);
  geometry::write_surface_mesh(dir / "sphere.off",
                               fdem::hertz::sphere_surface(kRadius, fdem::hertz::kGeometryEdge * k,
                                                           fdem::hertz::kGeometryPatch * k));
  const double gap = 2e-4 * k * k;  // the series' initial clearance
  const io::Json scene_json = {
      {"name", "calculix-sphere-" + tag},
      {"duration", 1.0},
      {"materials",
       {{"soft",
         {{"density", m.density}, {"young", m.young}, {"poisson", m.poisson}, {"law", "linear"}}}}},
      {"bodies",
       {{{"name", "ball"},
         {"material", "soft"},
         {"model", "fem"},
         {"shape",
          {{"type", "mesh"},
           {"file", "sphere.off"},
           {"element_size", fdem::hertz::level_size(s, k, true)},
           {"element_size_focus", {0.0, 0.0, -kRadius}},
           {"element_size_focus_radius", 0.02 * k},
           {"element_size_growth", 0.15 * s},
           {"element_size_far", 0.0125 * s}}},
         {"position", {0.0, 0.0, kRadius + gap}},
         {"velocity", {0.0, 0.0, -speed}}},
        {{"name", "floor"},
         {"material", "soft"},
         {"shape", {{"type", "plane"}, {"point", {0.0, 0.0, 0.0}}, {"normal", {0.0, 0.0, 1.0}}}}}}},
      {"contact", {{"law", "potential"}}},
      {"record", {{"force_on", "ball"}}}};
  std::ofstream(dir / "scene.json") << scene_json.dump(2) << "\n";  // to rerun it by hand
  const scene::SceneDef scene = scene::parse_scene(scene_json, dir / "scene.json", "");
  const peers::Adapter& a = peers::find_adapter("calculix");
  // The step count only bounds the end: the adapter stops 1.2 Hertz times after the touch.
  const run::RunResult r = peers::run_peer(a, peers::peer_executable(a, ""), scene,
                                           {.dt = 1e-4, .steps = 10'000}, dir / "calculix");
  const auto& j = r.summary;
  const double mass = j.at("calculix_meshed_mass").get<double>();
  const fdem::scenes::Hertz h =
      fdem::hertz::hertz_impact(mass, kRadius, m.young / (1 - m.poisson * m.poisson), speed);
  return {.s = s,
          .err_peak = j.at("peak_force").get<double>() / h.force - 1,
          .err_filtered = j.at("peak_force_filtered").get<double>() / h.force - 1,
          .err_duration = j.at("contact_duration").get<double>() / h.duration - 1,
          .impulse_ratio = j.at("impulse").get<double>() / (2 * mass * speed),
          .cpu = j.at("cpu_seconds").get<double>(),
          .nodes = j.at("calculix_nodes").get<long>()};
}

struct Limit {
  RichardsonRate peak, duration;
};

// The sequence at refinements s, s/√2, s/2 and its Richardson limits (filtered peak, duration).
Limit calculix_sequence(double a_over_r, double s0, std::vector<Measured>& levels) {
  for (int i = 0; i < 3; ++i) {
    const double s = s0 / std::pow(std::sqrt(2.0), i);
    levels.push_back(
        calculix_level(a_over_r, s, std::to_string(a_over_r) + "-" + std::to_string(i)));
    const Measured& l = levels.back();
    std::printf(
        "calculix a/R %.3f s %.3f nodes %ld (quarter) cpu %.1f s: peak %+.3f %% filtered "
        "%+.3f %% duration %+.3f %% impulse/2mv %.5f\n",
        a_over_r, s, l.nodes, l.cpu, 100 * l.err_peak, 100 * l.err_filtered, 100 * l.err_duration,
        l.impulse_ratio);
  }
  const double r = std::sqrt(2.0);
  return {
      richardson_rate(levels[0].err_filtered, levels[1].err_filtered, levels[2].err_filtered, r),
      richardson_rate(levels[0].err_duration, levels[1].err_duration, levels[2].err_duration, r)};
}

// The reference: the dynamic finite sphere (small strain, linear, frictionless, rigid plane:
// CalculiX's model exactly) at the nominal mass, filtered peak and duration from Hertz.
struct Reference {
  double filtered = 0, duration = 0;
};
Reference reference(double a_over_r) {
  const Material m = fdem::scenes::rubbery();
  const auto d = reference::finite_sphere_impact_dynamic(m.young, m.poisson, m.density, kRadius,
                                                         fdem::hertz::speed_for(a_over_r, m));
  return {d.filtered_peak_force / d.hertz_peak_force - 1, d.duration / d.hertz_duration - 1};
}

// Label calculix (CI): one coarse level, a/R = 0.107 at s = 1 (1 078 nodes in the quarter, about
// 40 s of ccx CPU on an idle core; the reference 3 s).
TEST(CalculiX, CoarseSphereConservesMomentumAndLiesOnTheStiffSideOfTheFiniteSphere) {
  const Measured l = calculix_level(0.107, 1.0, "ci");
  const Reference ref = reference(0.107);
  std::printf("reference (dynamic finite sphere): filtered peak %+.3f %%, duration %+.3f %%\n",
              100 * ref.filtered, 100 * ref.duration);
  // An elastic frictionless impact returns 2mv; the implicit scheme's numerical damping (HHT
  // α = −0.05) takes only vibration energy, which lowers the rebound by its share of ½mv²: the
  // reference leaves 1e-4 in vibration (docs/physics.md, 6b), 1e-3 is ten times that.
  EXPECT_NEAR(l.impulse_ratio, 1.0, 1e-3);
  // Displacement-based 4-node tetrahedra are stiffer than the continuum, so a coarse level's peak
  // lies above the reference and its duration below; the penalty layer (slope 50 E/h) is the one
  // softening term, p0 h/(50 E) of the approach: 0.5 % at this level, the margin allowed.
  EXPECT_GT(l.err_filtered, ref.filtered - 0.005);
  EXPECT_LT(l.err_duration, ref.duration + 0.005);
  // The 2 % on the peak: the finite sphere's own correction to Hertz is 5 % here, so a
  // level within 2 % of it has resolved more than half of it. Not on one coarse level's duration:
  // its end is the penalty release of the last few nodes, whose tail moved the duration by 0.8
  // point between two meshes of this level (the sphere 0.24 mm above the plane or touching it:
  // −5.47 against −4.65 %); the duration is gated on the limits (calculix-full).
  EXPECT_NEAR(l.err_filtered, ref.filtered, 0.02);
}

// asperity's sequence on the same sphere and law (scenes/hertz_series.hpp's block levels, the
// linear law) at s, s/√2, s/2, and its Richardson limits.
Limit asperity_sequence(double a_over_r, double s0) {
  Material m = fdem::scenes::rubbery();
  const double speed = fdem::hertz::speed_for(a_over_r, m);
  std::vector<fdem::hertz::Level> l;
  for (int i = 0; i < 3; ++i) {
    l.push_back(fdem::hertz::run_level(fdem::hertz::Setup::block, s0 / std::pow(std::sqrt(2.0), i),
                                       speed, true, {.law = ElasticLaw::linear}));
    std::printf(
        "asperity a/R %.3f s %.3f tets %ld cpu %.1f s: peak %+.3f %% filtered %+.3f %% "
        "duration %+.3f %% impulse/2mv %.5f\n",
        a_over_r, l.back().s, l.back().tets, l.back().cpu, 100 * l.back().err_force,
        100 * l.back().err_force_filtered, 100 * l.back().err_duration, l.back().impulse_ratio);
  }
  const double r = std::sqrt(2.0);
  return {
      richardson_rate(l[0].err_force_filtered, l[1].err_force_filtered, l[2].err_force_filtered, r),
      richardson_rate(l[0].err_duration, l[1].err_duration, l[2].err_duration, r)};
}

// The gate: the two limits within 2 % of each other, or within their combined estimated
// error (each limit's error taken as its finest level's distance from it, the Richardson
// estimate) when that is larger; the tolerance used is printed.
void expect_limits_agree(const char* what, const RichardsonRate& a, const RichardsonRate& c) {
  const double tol = std::max(0.02, std::abs(a.finest_error) + std::abs(c.finest_error));
  std::printf(
      "%s: asperity %+.3f %% (order %.2f, ±%.3f), calculix %+.3f %% (order %.2f, ±%.3f), "
      "apart %.3f point, tolerance %.3f\n",
      what, 100 * a.limit, a.order, 100 * std::abs(a.finest_error), 100 * c.limit, c.order,
      100 * std::abs(c.finest_error), 100 * std::abs(a.limit - c.limit), 100 * tol);
  EXPECT_TRUE(std::isfinite(a.limit) && std::isfinite(c.limit)) << what;
  EXPECT_NEAR(a.limit, c.limit, tol) << what;
}

// Label calculix-full (outside CI): both codes converged at a/R = 0.08 and 0.15, filtered peak
// and duration limits compared. asperity at s = 2, √2, 1 (its meshes hold 4-5 times CalculiX's
// tetrahedra at the same keys: TetGen's quality refinement against gmsh's), CalculiX at s = √2,
// 1, 1/√2. About 10 min of CPU per a/R.
class CalculiXFull : public ::testing::TestWithParam<double> {};
TEST_P(CalculiXFull, LimitsAgreeWithAsperity) {
  const double a_over_r = GetParam();
  std::vector<Measured> levels;
  const Limit c = calculix_sequence(a_over_r, std::sqrt(2.0), levels);
  const Limit a = asperity_sequence(a_over_r, 2.0);
  expect_limits_agree("filtered peak", a.peak, c.peak);
  expect_limits_agree("duration", a.duration, c.duration);
}
INSTANTIATE_TEST_SUITE_P(Spheres, CalculiXFull, ::testing::Values(0.08, 0.15));

// ---- Particles (issue 29, item 3, bullets 2 and 3) ----
//
// A particle striking a fixed plane at its strike point (the study's `lowest` placement: its
// lowest vertex first, falling straight down, no rotation), the same scene file run by asperity
// and by the CalculiX peer. The surface is the particle simplified to 500 triangles (the study's
// resolutions; `asperity mesh --faces 500`), which both codes mesh as its facets. The material,
// speed and element-size keys are the sphere's (E = 10 MPa, ν = 0.3, ρ = 1000 kg/m³, linear,
// frictionless, 0.2 m/s; 4s mm at the strike point within 20 mm, growth 0.15s, cap 12.5s mm)
// because these rocks (equivalent radius 0.11 m) are the sphere's size: the contact is then
// resolved by the keys the sphere cases converged with.
struct ParticleCase {
  const char* name;
  const char* set_name;  // an entry of data/particles/set.json; nullptr: `scan`
  const char* scan;      // a file of ../shared/data/scans/ (never committed), its `scale`
  double scale;
  const char* why;
};

constexpr double kParticleSpeed = 0.2;  // m/s
constexpr double kParticleGap = 2e-4;   // m, the lowest vertex above the plane at the start

// The particle's 500-triangle surface, written to `dir`/surface.off: generated from its set entry
// (written as `asperity particle --set` writes it, then read back, as `asperity mesh` reads it).
fs::path particle_surface(const ParticleCase& c, const fs::path& dir) {
  geometry::PipelineOptions o{.faces = 500, .tetrahedralize = false};
  fs::path source;
  if (c.set_name) {
    const io::Json set =
        io::read_json_file(fs::path(ASPERITY_SOURCE_DIR) / "data/particles/set.json");
    for (const io::Json& e : set.at("particles")) {
      if (e.at("name") != c.set_name) continue;
      const geometry::ParticleDef d{.seed = e.at("seed").get<std::uint64_t>(),
                                    .size = e.at("size"),
                                    .elongation = e.at("elongation"),
                                    .flatness = e.at("flatness"),
                                    .angularity = e.at("angularity"),
                                    .roughness = e.at("roughness"),
                                    .faces = e.at("faces")};
      source = dir / (std::string(c.set_name) + ".off");
      geometry::write_surface_mesh(source, geometry::random_particle(d));
    }
  } else {
    source = fs::path(ASPERITY_SOURCE_DIR) / "../shared/data/scans" / c.scan;
    o.read.scale = c.scale;
  }
  EXPECT_FALSE(source.empty()) << c.name << ": no such particle";
  const geometry::PreparedParticle p = geometry::prepare_particle(source, o);
  geometry::write_surface_mesh(dir / "surface.off", p.surface);
  return dir / "surface.off";
}

// The scene of level s: the surface's lowest vertex kParticleGap above the plane z = 0, its
// centroid above it (no rotation), graded to that vertex.
io::Json particle_scene(const ParticleCase& c, const fs::path& surface, double s) {
  const geometry::PreparedParticle p =
      geometry::prepare_particle(surface, {.tetrahedralize = false});
  Eigen::Index low = 0;
  p.surface.vertices.row(2).minCoeff(&low);
  const Vec3 lowest = p.surface.vertices.col(low), centroid = p.props.centroid;
  const Material m = fdem::scenes::rubbery();
  return {
      {"name", std::string(c.name) + "-s" + std::to_string(s)},
      {"duration", 0.05},
      {"materials",
       {{"soft",
         {{"density", m.density},
          {"young", m.young},
          {"poisson", m.poisson},
          {"law", "linear"},
          {"friction", 0}}}}},
      {"bodies",
       {{{"name", "particle"},
         {"material", "soft"},
         {"model", "fem"},
         {"shape",
          {{"type", "mesh"},
           {"file", surface.string()},
           {"element_size", 0.004 * s},
           {"element_size_focus", {lowest.x(), lowest.y(), lowest.z()}},
           {"element_size_focus_radius", 0.02},
           {"element_size_growth", 0.15 * s},
           {"element_size_far", 0.0125 * s}}},
         {"position", {0.0, 0.0, kParticleGap + centroid.z() - lowest.z()}},
         {"velocity", {0.0, 0.0, -kParticleSpeed}}},
        {{"name", "floor"},
         {"material", "soft"},
         {"shape", {{"type", "plane"}, {"point", {0.0, 0.0, 0.0}}, {"normal", {0.0, 0.0, 1.0}}}}}}},
      {"contact", {{"law", "potential"}, {"penalty_alpha", 10}}},
      {"record", {{"force_on", "particle"}, {"end_after_separation", 0.002}}}};
}

// A sequence's estimate: Richardson's limit where the decrements fall geometrically (q > 1),
// else the finest level with its last decrement as the error (reports/peers/calculix/README.md).
struct Estimate {
  double value = 0, error = 0, order = std::nan("");
};
Estimate estimate(double f1, double f2, double f3) {
  const RichardsonRate r = richardson_rate(f1, f2, f3, std::sqrt(2.0));
  if ((f1 - f2) / (f2 - f3) > 1) return {r.limit, std::abs(r.finest_error), r.order};
  return {f3, std::abs(f2 - f3)};
}

struct Side {
  std::vector<double> filtered, duration, cpu;  // N, s, s per level
};

void expect_particle_estimates_agree(const char* what, const std::vector<double>& a,
                                     const std::vector<double>& c) {
  const Estimate ea = estimate(a[0], a[1], a[2]), ec = estimate(c[0], c[1], c[2]);
  // The 2 %, or the two estimates' combined error when larger.
  const double tol = std::max(0.02, (ea.error + ec.error) / std::abs(ec.value));
  std::printf(
      "%s: asperity %.6g (order %.2f, ±%.3f %%), calculix %.6g (order %.2f, ±%.3f %%), apart "
      "%.3f %%, tolerance %.3f %%\n",
      what, ea.value, ea.order, 100 * ea.error / std::abs(ea.value), ec.value, ec.order,
      100 * ec.error / std::abs(ec.value), 100 * std::abs(ea.value / ec.value - 1), 100 * tol);
  EXPECT_NEAR(ea.value / ec.value, 1.0, tol) << what;
}

// Label calculix-full (outside CI): both codes at s = 2√2, 2, √2 on the same scene files. At the
// same keys gmsh's Delaunay makes about a fifth of TetGen's quality tetrahedra, and the whole
// particle costs ccx four quarters: these levels (about 0.7k, 1.4k and 2.7k nodes for ccx) are
// what this machine's CPU allows; the measured levels are in reports/peers/calculix/particles.csv.
class CalculiXParticle : public ::testing::TestWithParam<ParticleCase> {};
TEST_P(CalculiXParticle, LimitsAgreeWithAsperity) {
  const ParticleCase& c = GetParam();
  const fs::path dir = scratch(std::string("particle-") + c.name);
  if (c.scan && !fs::exists(fs::path(ASPERITY_SOURCE_DIR) / "../shared/data/scans" / c.scan))
    GTEST_SKIP() << c.scan << ": the scans (../shared/data/scans/) are not on this machine";
  const fs::path surface = particle_surface(c, dir);
  Side asp, ccx;
  const peers::Adapter& a = peers::find_adapter("calculix");
  for (int i = 0; i < 3; ++i) {
    const double s = 2 * std::sqrt(2.0) / std::pow(std::sqrt(2.0), i);
    const fs::path level = dir / std::to_string(i);  // the level, 0 the coarsest
    fs::create_directories(level);
    const io::Json json = particle_scene(c, surface, s);
    std::ofstream(level / "scene.json") << json.dump(2) << "\n";  // to rerun it by hand
    const scene::SceneDef scene = scene::parse_scene(json, level / "scene.json", "");
    const run::RunResult own = run::run_scene(scene, {.keep_rows = false});
    ASSERT_EQ(own.status, "ok") << own.message;
    const run::RunResult peer = peers::run_peer(a, peers::peer_executable(a, ""), scene,
                                                {.dt = 1e-4, .steps = 500}, level / "calculix");
    for (auto [side, j] : {std::pair{&asp, &own.summary}, std::pair{&ccx, &peer.summary}}) {
      side->filtered.push_back(j->at("peak_force_filtered").get<double>());
      side->duration.push_back(j->at("contact_duration").get<double>());
      side->cpu.push_back(j->at("cpu_seconds").get<double>());
    }
    std::printf(
        "%s s %.3f: asperity filtered %.4g N duration %.5g s cpu %.1f s; calculix (%ld nodes) "
        "filtered %.4g N duration %.5g s cpu %.1f s, impulse %.4g against asperity's %.4g\n",
        c.name, s, asp.filtered.back(), asp.duration.back(), asp.cpu.back(),
        peer.summary.at("calculix_nodes").get<long>(), ccx.filtered.back(), ccx.duration.back(),
        ccx.cpu.back(), peer.summary.at("impulse").get<double>(),
        own.summary.at("impulse").get<double>());
  }
  expect_particle_estimates_agree("filtered peak", asp.filtered, ccx.filtered);
  expect_particle_estimates_agree("duration", asp.duration, ccx.duration);
}
INSTANTIATE_TEST_SUITE_P(
    Particles, CalculiXParticle,
    ::testing::Values(
        ParticleCase{"rock_02", "rock_02", nullptr, 1,
                     "a generated rock (flat, 0.23 m): the set's rock-like shapes"},
        ParticleCase{"rock_04", "rock_04", nullptr, 1, "a second generated rock (0.20 m)"},
        ParticleCase{"scan_AAA", nullptr, "ibois-augmented-stacking-stones/low_res_AAA.ply", 1,
                     "a scanned quarry stone (metres, clean: SOURCE.md)"}),
    [](const ::testing::TestParamInfo<ParticleCase>& i) { return std::string(i.param.name); });

}  // namespace
}  // namespace asperity
