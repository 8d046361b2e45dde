// CalculiX beside asperity on the deformable sphere of the Hertz gates (issue 29): the CalculiX
// peer (peers/calculix.cpp) runs the sphere of scenes/hertz_spheres.hpp as a contract scene: one
// coarse level held against the dynamic finite-sphere reference (validation/reference/) in CI,
// and sequences of whole-field refinements whose Richardson limits are held against asperity's
// own (label calculix-full).
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
#include "solver/geometry/write_mesh.hpp"
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
  fdem::hertz::Rate peak, duration;
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
  return {fdem::hertz::richardson(levels[0].err_filtered, levels[1].err_filtered,
                                  levels[2].err_filtered, r),
          fdem::hertz::richardson(levels[0].err_duration, levels[1].err_duration,
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
  return {fdem::hertz::richardson(l[0].err_force_filtered, l[1].err_force_filtered,
                                  l[2].err_force_filtered, r),
          fdem::hertz::richardson(l[0].err_duration, l[1].err_duration, l[2].err_duration, r)};
}

// The gate: the two limits within 2 % of each other, or within their combined estimated
// error (each limit's error taken as its finest level's distance from it, the Richardson
// estimate) when that is larger; the tolerance used is printed.
void expect_limits_agree(const char* what, const fdem::hertz::Rate& a, const fdem::hertz::Rate& c) {
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

}  // namespace
}  // namespace asperity
