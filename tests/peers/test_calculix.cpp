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
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "peers/calculix_rows.hpp"
#include "peers/peer.hpp"
#include "scenes/hertz_series.hpp"
#include "solver/core/richardson.hpp"
#include "solver/geometry/mesh_pipeline.hpp"
#include "solver/geometry/random_particle.hpp"
#include "solver/geometry/write_mesh.hpp"
#include "solver/io/atomic_file.hpp"
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

// Level n's refinement s = √2ⁿ as one double, whichever triple holds it and whatever wrote the
// scene: a power of two, or √2 scaled by one (both exact). asperity's mesher is not continuous in
// its element-size keys: computed as coarsest / √2^i, s = 1 was 1 − 2⁻⁵² in the triple from s = 2
// and 1 in the triple from √2, and the scan AAA's two meshes of "s = 1" differed (5 481 and 5 411
// nodes; filtered peak 54.87 and 54.93 N, duration 9.061 and 9.040 ms: reports/peers/calculix/
// README.md, "One level, one mesh"); so did the sphere's at s = 1 at every a/R (0.08: 80 588 and
// 80 249 tetrahedra, "The sphere gates at exact s"). Both gates' levels come from here. gmsh reads
// the keys at 12 digits, so CalculiX's meshes do not see such a difference.
double level_s(int n) {
  return std::ldexp(n % 2 != 0 ? std::numbers::sqrt2 : 1.0, static_cast<int>(std::floor(n / 2.0)));
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
  peers::run_peer(a, peers::peer_executable(a, ""), scene, {.dt = 1e-4, .steps = 10'000},
                  dir / "calculix");
  // The measures as reports/peers/calculix/levels.csv records them (peers/calculix_rows.hpp):
  // `calculix_rows levels` writes this level's row from the same folder.
  const peers::calculix_rows::SphereLevel l = peers::calculix_rows::sphere_level(dir / "calculix");
  return {.s = s,
          .err_peak = l.err_peak,
          .err_filtered = l.err_filtered,
          .err_duration = l.err_duration,
          .impulse_ratio = l.impulse_ratio,
          .cpu = l.cpu,
          .nodes = l.nodes};
}

// A sequence's estimates (filtered peak, duration): Richardson's limit where the observed order is
// trusted, else the finest level with an error of the last change's size or more
// (solver/core/richardson.hpp, richardson_estimate).
struct Limit {
  RichardsonEstimate peak, duration;
};

// The sequence at refinements √2ⁿ, √2ⁿ⁻¹, √2ⁿ⁻² (level_s; n the coarsest) and its estimates
// (filtered peak, duration).
Limit calculix_sequence(double a_over_r, int coarsest, std::vector<Measured>& levels) {
  for (int i = 0; i < 3; ++i) {
    const double s = level_s(coarsest - i);
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
  return {richardson_estimate(levels[0].err_filtered, levels[1].err_filtered,
                              levels[2].err_filtered, r),
          richardson_estimate(levels[0].err_duration, levels[1].err_duration,
                              levels[2].err_duration, r)};
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
  // The 2 %, on the peak and the duration: the finite sphere's own correction to Hertz is
  // 5 % (peak) and −3.3 % (duration) here, so a level within 2 % of it has resolved more than half
  // of it. The duration measured −4.64 % (2026-12-07; −4.65 % for this level with the sphere
  // touching the plane at t = 0): the 0.8 point it was held apart by before (−5.47 %) was the
  // contact's start placed up to one increment late (scene_to_calculix.py, with_contact_ends),
  // not the penalty release at its end.
  EXPECT_NEAR(l.err_filtered, ref.filtered, 0.02);
  EXPECT_NEAR(l.err_duration, ref.duration, 0.02);
}

// asperity's sequence on the same sphere and law (scenes/hertz_series.hpp's block levels, the
// linear law) at s = √2ⁿ, √2ⁿ⁻¹, √2ⁿ⁻² (level_s; n the coarsest), and its estimates. Until
// 2026-12-07 the levels were 2 / √2^i, so "√2" was one double low and "1" two (1.414213562373095,
// 0.9999999999999998), which asperity's mesher can mesh differently (level_s).
Limit asperity_sequence(double a_over_r, int coarsest) {
  Material m = fdem::scenes::rubbery();
  const double speed = fdem::hertz::speed_for(a_over_r, m);
  std::vector<fdem::hertz::Level> l;
  for (int i = 0; i < 3; ++i) {
    l.push_back(fdem::hertz::run_level(fdem::hertz::Setup::block, level_s(coarsest - i), speed,
                                       true, {.law = ElasticLaw::linear}));
    std::printf(
        "asperity a/R %.3f s %.3f tets %ld cpu %.1f s: peak %+.3f %% filtered %+.3f %% "
        "duration %+.3f %% impulse/2mv %.5f\n",
        a_over_r, l.back().s, l.back().tets, l.back().cpu, 100 * l.back().err_force,
        100 * l.back().err_force_filtered, 100 * l.back().err_duration, l.back().impulse_ratio);
  }
  const double r = std::sqrt(2.0);
  return {richardson_estimate(l[0].err_force_filtered, l[1].err_force_filtered,
                              l[2].err_force_filtered, r),
          richardson_estimate(l[0].err_duration, l[1].err_duration, l[2].err_duration, r)};
}

// The gate: the two estimates within 2 % of each other, or within their combined
// estimated error when that is larger; the tolerance used is printed, and whether each order was
// trusted (an untrusted one leaves the finest level, with its error of 3 last changes).
void expect_limits_agree(const char* what, const RichardsonEstimate& a,
                         const RichardsonEstimate& c) {
  const double tol = std::max(0.02, a.error + c.error);
  std::printf(
      "%s: asperity %+.3f %% (order %.2f%s, ±%.3f), calculix %+.3f %% (order %.2f%s, ±%.3f), "
      "apart %.3f point, tolerance %.3f\n",
      what, 100 * a.value, a.order, a.trusted ? "" : " refused", 100 * a.error, 100 * c.value,
      c.order, c.trusted ? "" : " refused", 100 * c.error, 100 * std::abs(a.value - c.value),
      100 * tol);
  EXPECT_TRUE(std::isfinite(a.value) && std::isfinite(c.value)) << what;
  EXPECT_NEAR(a.value, c.value, tol) << what;
}

// Label calculix-full (outside CI): both codes converged at a/R = 0.08, 0.15 and 0.107 (listed
// last, so that /0 and /1 keep naming 0.08 and 0.15), filtered peak and duration limits compared.
// asperity at s = 2, √2, 1 (its meshes hold 4-5 times CalculiX's tetrahedra at the same keys:
// TetGen's quality refinement against gmsh's), CalculiX at s = √2, 1, 1/√2. About 10 min of CPU per
// a/R.
class CalculiXFull : public ::testing::TestWithParam<double> {};
TEST_P(CalculiXFull, LimitsAgreeWithAsperity) {
  const double a_over_r = GetParam();
  std::vector<Measured> levels;
  const Limit c = calculix_sequence(a_over_r, 1, levels);  // s = √2, 1, 1/√2
  const Limit a = asperity_sequence(a_over_r, 2);          // s = 2, √2, 1
  expect_limits_agree("filtered peak", a.peak, c.peak);
  expect_limits_agree("duration", a.duration, c.duration);
}
INSTANTIATE_TEST_SUITE_P(Spheres, CalculiXFull, ::testing::Values(0.08, 0.15, 0.107));

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
  // The coarsest of the gate's three levels, n: s = √2ⁿ, then √2ⁿ⁻¹, √2ⁿ⁻² (level_s), and why
  // there.
  int coarsest = 3;
  const char* why_levels = "the levels this machine's CPU allows for ccx's whole particle";
};

constexpr double kParticleSpeed = 0.2;  // m/s
constexpr double kParticleGap = 2e-4;   // m, the lowest vertex above the plane at the start

// The particle's 500-triangle surface, written to `dir`/surface.off: generated from its set entry
// (written as `asperity particle --set` writes it, then read back, as `asperity mesh` reads it).
fs::path particle_surface(const ParticleCase& c, const fs::path& dir) {
  geometry::PipelineOptions o{.faces = 500, .tetrahedralize = false};
  fs::path source;
  if (c.set_name) {
    const fs::path file = fs::path(ASPERITY_SOURCE_DIR) / "data/particles/set.json";
    const io::Json set = io::read_json_file(file);
    const io::JsonReader list = io::JsonReader(set, file, "").child("particles");
    for (std::size_t i = 0, n = list.require_array(); i < n; ++i) {
      if (list.at(i).string("name") != c.set_name) continue;
      source = dir / (std::string(c.set_name) + ".off");
      geometry::write_surface_mesh(
          source, geometry::random_particle(geometry::read_particle_def(list.at(i))));
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

struct Side {
  std::vector<double> filtered, duration, cpu;  // N, s, s per level
};

// The particle gate's verdict on two sequences (coarse to fine, refined by √2), printed: the
// estimates within the 2 % of each other, or within their combined error when larger.
// Richardson's limit only at a trusted order (solver/core/richardson.hpp): the scan AAA's asperity
// peak, whose changes fall 4.95 then 0.09 N ("order 11.75") over s = 2√2, 2, √2, is its finest
// level ± 3 last changes, not a limit ± 0.003 %.
struct Agreement {
  RichardsonEstimate asperity, calculix;
  double apart = 0, tolerance = 0;  // relative to CalculiX's estimate
  bool agree = false;
};
Agreement particle_estimates(const char* what, const std::vector<double>& a,
                             const std::vector<double>& c) {
  const double r = std::sqrt(2.0);
  Agreement g{.asperity = richardson_estimate(a[0], a[1], a[2], r),
              .calculix = richardson_estimate(c[0], c[1], c[2], r)};
  const RichardsonEstimate &ea = g.asperity, &ec = g.calculix;
  g.tolerance = std::max(0.02, (ea.error + ec.error) / std::abs(ec.value));
  g.apart = std::abs(ea.value / ec.value - 1);
  g.agree = g.apart <= g.tolerance;
  std::printf(
      "%s: asperity %.6g (order %.2f%s, ±%.4g, %.3f %%), calculix %.6g (order %.2f%s, ±%.4g, "
      "%.3f %%), apart %.3f %%, tolerance %.3f %%: %s\n",
      what, ea.value, ea.order, ea.trusted ? "" : " refused", ea.error,
      100 * ea.error / std::abs(ea.value), ec.value, ec.order, ec.trusted ? "" : " refused",
      ec.error, 100 * ec.error / std::abs(ec.value), 100 * g.apart, 100 * g.tolerance,
      g.agree ? "agree" : "differ");
  return g;
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
    const double s = level_s(c.coarsest - i);
    const fs::path level = dir / std::to_string(i);  // the level, 0 the coarsest
    fs::create_directories(level);
    const io::Json json = particle_scene(c, surface, s);
    std::ofstream(level / "scene.json") << json.dump(2) << "\n";  // to rerun it by hand
    const scene::SceneDef scene = scene::parse_scene(json, level / "scene.json", "");
    const run::RunResult own = run::run_scene(scene, {.keep_rows = false});
    ASSERT_EQ(own.status, "ok") << own.message;
    // Kept beside CalculiX's folder, as `crosscheck --out LEVEL` keeps it: `calculix_rows
    // particles` writes both codes' rows from LEVEL (its force history is not kept: 1e4 steps).
    fs::create_directories(level / "asperity");
    io::write_atomically(level / "asperity" / "summary.json", own.summary.dump(2) + "\n");
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
  EXPECT_TRUE(particle_estimates("filtered peak", asp.filtered, ccx.filtered).agree);
  EXPECT_TRUE(particle_estimates("duration", asp.duration, ccx.duration).agree);
}
INSTANTIATE_TEST_SUITE_P(
    Particles, CalculiXParticle,
    ::testing::Values(
        ParticleCase{"rock_02", "rock_02", nullptr, 1,
                     "a generated rock (flat, 0.23 m): the set's rock-like shapes"},
        ParticleCase{"rock_04", "rock_04", nullptr, 1, "a second generated rock (0.20 m)"},
        ParticleCase{"scan_AAA", nullptr, "ibois-augmented-stacking-stones/low_res_AAA.ply", 1,
                     "a scanned quarry stone (metres, clean: SOURCE.md)", 1,
                     "the first triple where both codes' orders are trusted (peak 2.63 and 2.70): "
                     "over s = 2√2, 2, √2 both stall (changes 4.95, 0.09 N and 6.98, 1.34 N), "
                     "then fall 3.3-3.8 N at s = 1 (reports/peers/calculix/README.md); ccx's "
                     "s = 1/√2 costs 330 s"}),
    [](const ::testing::TestParamInfo<ParticleCase>& i) { return std::string(i.param.name); });

// ---- The committed levels, read back (label unit: runs neither code) ----
//
// reports/peers/calculix/levels.csv (the sphere's CalculiX levels) and particles.csv (both codes'
// particle levels), measured in 2026-12, through the same estimate and verdict as the gates above.
// The README's figures marked "recomputed" are this test's printed lines (`ctest -R
// CalculiXRecordedLevels -V`), from the committed levels, not from a rerun.

// A CSV's rows as name -> field (the committed files: no quoted fields).
std::vector<std::map<std::string, std::string>> read_rows(const fs::path& file) {
  std::ifstream in(file);
  EXPECT_TRUE(in) << file;
  const auto split = [](const std::string& line) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
    if (!line.empty() && line.back() == ',') f.emplace_back();
    return f;
  };
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> f = split(line);
    std::map<std::string, std::string>& row = rows.emplace_back();
    for (std::size_t i = 0; i < header.size() && i < f.size(); ++i) row[header[i]] = f[i];
  }
  return rows;
}

const fs::path kRecorded = fs::path(ASPERITY_SOURCE_DIR) / "reports/peers/calculix";

// A column of the rows that match `key` = `value` on every pair, in file order.
std::vector<double> column(const std::vector<std::map<std::string, std::string>>& rows,
                           const std::vector<std::pair<std::string, std::string>>& match,
                           const std::string& name) {
  std::vector<double> v;
  for (const auto& row : rows) {
    bool all = true;
    for (const auto& [key, value] : match) all = all && row.at(key) == value;
    if (all) v.push_back(std::stod(row.at(name)));
  }
  return v;
}

// calculix_rows (peers/calculix_rows.hpp) on level folders written here: a sphere level's row
// against Hertz at its meshed mass, and a particle level's asperity row with its keys read from
// the gate's scene.json (no CalculiX folder).
TEST(CalculiXRecordedLevels, RowsComeFromTheLevelFolder) {
  namespace rows = peers::calculix_rows;
  const fs::path dir = scratch("rows");
  const Material m = fdem::scenes::rubbery();
  const double speed = fdem::hertz::speed_for(0.107, m), mass = 4.2;
  const fdem::scenes::Hertz h =
      fdem::hertz::hertz_impact(mass, kRadius, m.young / (1 - m.poisson * m.poisson), speed);
  fs::create_directories(dir / "sphere" / "calculix");
  std::ofstream(dir / "sphere" / "calculix" / "input.json")
      << io::Json{{"young", m.young},   {"poisson", m.poisson}, {"density", m.density},
                  {"radius", kRadius},  {"speed", speed},       {"size", 0.00398},
                  {"far", 0.0125 * 0.5}}
             .dump();
  std::ofstream(dir / "sphere" / "calculix" / "summary.json") << io::Json{
      {"calculix_meshed_mass", mass},
      {"calculix_increments_per_hertz_time", 100},
      {"calculix_nodes", 1078},
      {"calculix_tets", 4283},
      {"cpu_seconds", 37.54},
      {"peak_force", 1.06 * h.force},
      {"peak_force_filtered", 1.05 * h.force},
      {"contact_duration", 0.95 * h.duration},
      {"impulse", 0.9998 * 2 * mass * speed}}.dump();
  EXPECT_EQ(rows::sphere_fields(rows::sphere_level(dir / "sphere" / "calculix")),
            (std::vector<std::string>{"0.107", "0.5000", "100", "3.980", "1078", "4283", "37.5",
                                      "+6.000", "+5.000", "-5.000", "0.99980"}));
  fs::create_directories(dir / "particle" / "asperity");
  std::ofstream(dir / "particle" / "scene.json")
      << io::Json{{"bodies",
                   {{{"name", "floor"}},
                    {{"name", "particle"},
                     {"model", "fem"},
                     {"shape", {{"element_size", 0.004}, {"element_size_far", 0.0125}}}}}}}
             .dump();
  std::ofstream(dir / "particle" / "asperity" / "summary.json") << io::Json{
      {"recorded_body", "particle"},
      {"bodies",
       {{{"name", "floor"}, {"nodes", 8}},
        {{"name", "particle"}, {"nodes", 5411}, {"tets", 27448}}}},
      {"cpu_seconds", 11.59},
      {"steps", 10216},
      {"peak_force", 54.9991},
      {"peak_force_filtered", 54.9345},
      {"contact_duration", 9.0397e-3},
      {"impulse", 0.26421},
      {"restitution", 0.18361},
      {"first_contact_time", 1.00062e-3}}.dump();
  EXPECT_EQ(
      rows::particle_fields("scan_AAA", rows::particle_level(dir / "particle", "asperity")),
      (std::vector<std::string>{"scan_AAA", "asperity", "1.0000", "4.00", "5411", "27448", "11.6",
                                "10216", "55.00", "54.93", "9.040", "0.2642", "0.1836", "1.0006"}));
}

// The sphere: CalculiX's estimates of the filtered peak and the duration (% from Hertz) per a/R
// and triple of levels at T_H/100. Which orders are trusted: 6.4 (a/R = 0.08's peak: a jump,
// then a stall) is not. 0.08 and 0.15 were rerun by the gate with the contact's start fix
// (2026-12-07): 0.15's durations now fall, 0.89 then 0.65 point, order 0.89, trusted (before:
// 0.73 then 0.85, growing). 0.107's s = √2, 1, 1/√2 are the gate's levels since 2026-12-07
// (`Spheres/CalculiXFull.*/2`; the sphere 0.24 mm above the plane, where the first runs started
// touching it): peak order 3.75, duration 0.54 (changes 0.64, 0.53 point), both trusted, where the
// first runs' durations grew (0.12 then 0.63); its s = 2 row is still the first runs', so no
// triple starts there.
TEST(CalculiXRecordedLevels, SphereEstimatesRefuseTheStallsAndTheGrowingChanges) {
  const auto rows = read_rows(kRecorded / "levels.csv");
  struct Triple {
    const char* a_over_r;
    std::vector<std::string> s;
    bool peak_trusted, duration_trusted;
  };
  for (const Triple& t : {Triple{"0.080", {"1.4142", "1.0000", "0.7071"}, false, true},
                          Triple{"0.107", {"1.4142", "1.0000", "0.7071"}, true, true},
                          Triple{"0.150", {"1.4142", "1.0000", "0.7071"}, true, true}}) {
    std::vector<double> peak, duration;
    for (const std::string& s : t.s) {
      const std::vector<std::pair<std::string, std::string>> m = {
          {"a_over_r", t.a_over_r}, {"s", s}, {"increments_per_hertz_time", "100"}};
      const std::vector<double> p = column(rows, m, "filtered_peak_pct"),
                                d = column(rows, m, "duration_pct");
      ASSERT_EQ(p.size(), 1u) << t.a_over_r << " " << s;
      peak.push_back(p[0]);
      duration.push_back(d[0]);
    }
    const double r = std::sqrt(2.0);
    const RichardsonEstimate ep = richardson_estimate(peak[0], peak[1], peak[2], r),
                             ed = richardson_estimate(duration[0], duration[1], duration[2], r);
    std::printf(
        "sphere a/R %s s %s, %s, %s: filtered peak %+.3f %% ± %.3f (order %.2f%s), duration "
        "%+.3f %% ± %.3f (order %.2f%s)\n",
        t.a_over_r, t.s[0].c_str(), t.s[1].c_str(), t.s[2].c_str(), ep.value, ep.error, ep.order,
        ep.trusted ? "" : " refused", ed.value, ed.error, ed.order, ed.trusted ? "" : " refused");
    EXPECT_EQ(ep.trusted, t.peak_trusted) << t.a_over_r;
    EXPECT_EQ(ed.trusted, t.duration_trusted) << t.a_over_r;
    for (const auto& [e, v] : {std::pair{ep, peak}, std::pair{ed, duration}}) {
      if (!e.trusted) {
        EXPECT_GE(e.error, std::abs(v[1] - v[2])) << t.a_over_r;
      }
    }
  }
}

// The particles: the gate's verdict on each triple of committed levels. rock_02 and rock_04 at
// s = 2√2, 2, √2 (and rock_02's asperity over s = 2, √2, 1 against CalculiX's s = 2√2, 2, √2);
// the scan AAA over s = 2√2, 2, √2 (the gate as first run) and over its finest three, s = 2, √2,
// 1 (the gate's levels since its fourth level was measured, 2026-12-07).
struct Triple {
  const char* particle;
  std::vector<std::string> asperity_s, calculix_s;  // the CSV's `s`, coarse to fine
};
struct Levels {
  std::vector<double> peak[2], duration[2];  // [asperity, calculix]: N, ms
};
Levels levels_of(const std::vector<std::map<std::string, std::string>>& rows, const Triple& t) {
  Levels l;
  for (int code = 0; code < 2; ++code) {
    for (const std::string& s : code == 0 ? t.asperity_s : t.calculix_s) {
      const std::vector<std::pair<std::string, std::string>> m = {
          {"particle", t.particle}, {"code", code == 0 ? "asperity" : "calculix"}, {"s", s}};
      const std::vector<double> p = column(rows, m, "filtered_peak_n"),
                                d = column(rows, m, "duration_ms");
      EXPECT_EQ(p.size(), 1u) << t.particle << " " << s;
      l.peak[code].push_back(p.empty() ? std::nan("") : p[0]);
      l.duration[code].push_back(d.empty() ? std::nan("") : d[0]);
    }
  }
  std::printf("%s, asperity s = %s, %s, %s; calculix s = %s, %s, %s (N, ms)\n", t.particle,
              t.asperity_s[0].c_str(), t.asperity_s[1].c_str(), t.asperity_s[2].c_str(),
              t.calculix_s[0].c_str(), t.calculix_s[1].c_str(), t.calculix_s[2].c_str());
  return l;
}

TEST(CalculiXRecordedLevels, ParticleVerdictsUnderTheTrustedOrderRule) {
  const auto rows = read_rows(kRecorded / "particles.csv");
  struct Verdict {
    Triple levels;
    bool peak, duration;
  };
  const std::vector<std::string> coarse = {"2.8284", "2.0000", "1.4142"},
                                 fine = {"2.0000", "1.4142", "1.0000"},
                                 finest = {"1.4142", "1.0000", "0.7071"};
  const std::vector<Verdict> verdicts = {
      {{"rock_02", {"2.8284", "2", "1.4142"}, {"2.8284", "2", "1.4142"}}, true, true},
      {{"rock_02", {"2", "1.4142", "1.0000"}, {"2.8284", "2", "1.4142"}}, true, true},
      {{"rock_04", coarse, coarse}, true, true},
      {{"scan_AAA", coarse, coarse}, false, true},
      {{"scan_AAA", fine, fine}, true, true},
      {{"scan_AAA", finest, finest}, true, true}};
  for (const Verdict& v : verdicts) {
    const Levels l = levels_of(rows, v.levels);
    EXPECT_EQ(particle_estimates("filtered peak", l.peak[0], l.peak[1]).agree, v.peak)
        << v.levels.particle;
    EXPECT_EQ(particle_estimates("duration", l.duration[0], l.duration[1]).agree, v.duration)
        << v.levels.particle;
  }
}

// The scan AAA's peak at s = 1 and 1/√2 (2026-12-07), the measurement that decides which side was
// wrong on s = 2√2, 2, √2: neither. Each code's estimate from the first triple misses its own
// fourth level by far more than its error (asperity's stall, 58.21 ± 0.27 N, then 54.93 N;
// CalculiX's order-4.76 limit, 59.92 ± 0.32 N, then 56.42 N), so the 2.86 % between those estimates
// measured the levels, not the codes. Level for level the codes close in (CalculiX stiffer by
// 5.6, 3.5 and 2.8 % at s = 2, √2, 1, as gmsh's 2-3 times fewer tetrahedra make it on rock_02),
// and over the finest three both orders are refused (the changes grow: 0.09 then 3.28 N,
// 1.34 then 3.82 N), so the gate's agreement there is within their combined error (38 %) only:
// unresolved, not confirmed within 2 %.
TEST(CalculiXRecordedLevels, ScanAAAsFinerLevelsFindNeitherCodeWrong) {
  const auto rows = read_rows(kRecorded / "particles.csv");
  const Triple coarse{"scan_AAA", {"2.8284", "2.0000", "1.4142"}, {"2.8284", "2.0000", "1.4142"}},
      fine{"scan_AAA", {"2.0000", "1.4142", "1.0000"}, {"2.0000", "1.4142", "1.0000"}};
  const Levels c = levels_of(rows, coarse), f = levels_of(rows, fine);
  const Agreement first = particle_estimates("filtered peak", c.peak[0], c.peak[1]);
  // asperity's first triple stalls (changes 4.95, 0.09 N): refused, the finest level stands.
  EXPECT_FALSE(first.asperity.trusted);
  EXPECT_GT(first.asperity.order, kTrustedOrderMax);
  EXPECT_EQ(first.asperity.value, c.peak[0][2]);
  // Both codes' s = 1 lie outside their first triple's estimate ± its error.
  for (int code = 0; code < 2; ++code) {
    const RichardsonEstimate& e = code == 0 ? first.asperity : first.calculix;
    const double s1 = f.peak[code][2];
    std::printf("%s: s = 1 at %.2f N, %.1f errors below the first triple's %.2f ± %.2f N\n",
                code == 0 ? "asperity" : "calculix", s1, (e.value - s1) / e.error, e.value,
                e.error);
    EXPECT_GT(std::abs(s1 - e.value), 3 * e.error) << code;
  }
  // Level for level the codes approach each other.
  double previous = 1;
  for (std::size_t i = 0; i < 3; ++i) {
    const double stiffer = f.peak[1][i] / f.peak[0][i] - 1;
    EXPECT_GT(stiffer, 0) << i;
    EXPECT_LT(stiffer, previous) << i;
    previous = stiffer;
  }
  // The finest triple: no order trusted on either side; within the combined error only.
  const Agreement last = particle_estimates("filtered peak", f.peak[0], f.peak[1]);
  EXPECT_FALSE(last.asperity.trusted);
  EXPECT_FALSE(last.calculix.trusted);
  EXPECT_GT(last.apart, 0.02);
  EXPECT_TRUE(last.agree);
  // One level finer (s = √2, 1, 1/√2, 2026-12-07) both sequences are asymptotic: orders 2.63 and
  // 2.70 in the peak, 2.66 and 1.91 in the duration, all trusted; the limits lie 2.28 % (peak)
  // and 3.8 % (duration) apart, within their combined errors (3.4 and 5.2 %), not within 2 %.
  // (asperity's s = 1 is the gate's mesh of s = 1 since the levels are one double each,
  // level_s; with the mesh of 1 − 2⁻⁵² it was 2.05 % and 3.4 % within 3.2 and 4.7 %.)
  const Levels n =
      levels_of(rows, {"scan_AAA", {"1.4142", "1.0000", "0.7071"}, {"1.4142", "1.0000", "0.7071"}});
  for (const Agreement& g : {particle_estimates("filtered peak", n.peak[0], n.peak[1]),
                             particle_estimates("duration", n.duration[0], n.duration[1])}) {
    EXPECT_TRUE(g.asperity.trusted);
    EXPECT_TRUE(g.calculix.trusted);
    EXPECT_TRUE(g.agree);
    // Asymptotic on both sides, the combined error is 3.4 % (peak) and 5.2 % (duration), an
    // eighth of the 38-41 % one level coarser: under 6 %.
    EXPECT_LT(g.tolerance, 0.06);
  }
}

}  // namespace
}  // namespace asperity
