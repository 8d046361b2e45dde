// The study's table units on hand-made inputs: the published reference data read from
// data/study/, its refusal of a broken file, the per-particle classes, the reference's Richardson
// extrapolation and its geometry term.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "solver/core/error.hpp"
#include "solver/core/richardson.hpp"
#include "study/tables/tables.hpp"
#include "tests/study/case_files.hpp"

namespace asperity::study::tables {
namespace {
namespace fs = std::filesystem;

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path scratch(const std::string& name) {
  return test::scratch("study_tables", name);
}

TEST(PublishedStudy, ReadsZhangZsakiFigures) {
  const OJson p = read_published_study(ASPERITY_PUBLISHED_STUDY);
  // Zhang & Zsaki 2019: 50 particles x 4 resolutions, 4 s at 100 and 572 s at 1000 triangles,
  // peak force within 5 % and impulse within 6 % across resolutions.
  EXPECT_EQ(p["simulations"].get<int>(), 50 * 4);
  EXPECT_EQ(p["cpu_seconds_100"].get<double>(), 4.0);
  EXPECT_EQ(p["cpu_seconds_1000"].get<double>(), 572.0);
  EXPECT_DOUBLE_EQ(p["cpu_growth_100_1000"].get<double>(), 143.0);  // 572 / 4
  EXPECT_DOUBLE_EQ(p["peak_force_variation_max"].get<double>(), 0.05);
  EXPECT_DOUBLE_EQ(p["impulse_variation_max"].get<double>(), 0.06);
  // The summary's key order is the report's contract (study_report.py reads it by name).
  EXPECT_EQ(p.begin().key(), "source");
}

TEST(PublishedStudy, MissingFigureNamesFileAndKey) {
  const fs::path file = scratch("published") / "published.json";
  std::ofstream(file) << R"({"source": "x", "simulations": 200, "cpu_seconds_100": 4,
    "peak_force_variation_max": 0.05, "impulse_variation_max": 0.06})";
  try {
    read_published_study(file);
    FAIL() << "a file without cpu_seconds_1000 was accepted";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(file.string()), std::string::npos) << m;
    EXPECT_NE(m.find("cpu_seconds_1000"), std::string::npos) << m;
  }
}

Classification row(const std::string& particle, long resolution, const std::string& cls) {
  return {.particle = particle,
          .model = ModelKind::fem,
          .placement = Placement::centroid,
          .resolution = resolution,
          .lag = 0,
          .lag_rel = 0,
          .duration_ratio = 1,
          .skewness = 0,
          .skewness_reference = 0,
          .cls = cls};
}

TEST(ParticleClasses, UnionOfClassesAndCoarsestClass) {
  const fs::path dir = scratch("classes");
  write_particle_classes_table({row("a", 100, "shifted+tail"), row("a", 250, "overlapping"),
                                row("a", 500, "tail+asymmetric"), row("b", 100, "overlapping")},
                               dir);
  // a: every class met once, in order of first appearance; its coarsest (100) class as it was.
  EXPECT_EQ(read_text(dir / "particle_classes.csv"),
            "particle,model,placement,classes,coarsest_class\n"
            "a,fem,centroid,shifted+tail+asymmetric,shifted+tail\n"
            "b,fem,centroid,overlapping,overlapping\n");
}

TEST(StudyCsv, FieldsAsSummaryJsonWritesThemAndQuoted) {
  const fs::path dir = scratch("csv");
  // A number keeps its shortest round-trip form (0.1, not 0.1000000000000000055), null is empty,
  // and a message with a comma and a quote stays one field (RFC 4180).
  write_csv(dir / "t.csv", {"x", "n", "none", "message"},
            {{0.1, 3, OJson(), "bad \"mesh\", at 2"}});
  EXPECT_EQ(read_text(dir / "t.csv"), "x,n,none,message\n0.1,3,,\"bad \"\"mesh\"\", at 2\"\n");
}

// The reference's Richardson extrapolation (tables/study_cases.hpp, docs/study.md "Guidelines").
// Synthetic sequences v(h) = L + C h^p: the limit and the order are known exactly.
namespace richardson_tests {

std::vector<double> sequence(const std::vector<double>& h, double limit, double c, double p) {
  std::vector<double> v;
  for (double x : h) v.push_back(limit + c * std::pow(x, p));
  return v;
}

TEST(Richardson, ThreeLevelsRecoverTheOrderAndTheLimit) {
  // Three refined levels at h = 0.08, 0.04, 0.02 R (data/study/full.json): the observed order is
  // exact for a pure power law, so the limit is exact to round-off (1e-12 relative: the
  // bisection on the order runs to 2^-100 of its bracket).
  const std::vector<double> h = {0.08, 0.04, 0.02};
  for (double p : {1.0, 2.0, 2.5}) {
    const Extrapolation e = richardson(h, sequence(h, 1000.0, 3000.0, p));
    EXPECT_TRUE(e.observed) << p;
    EXPECT_NEAR(e.order, p, 1e-9) << p;
    EXPECT_NEAR(e.limit, 1000.0, 1e-9) << p;
    // the error estimate: Roache's 1.25 times the last correction, relative to the limit
    const double correction = 3000.0 * std::pow(0.02, p);
    EXPECT_NEAR(e.error, 1.25 * correction / 1000.0, 1e-12) << p;
  }
  // Sizes that do not halve (0.1, 0.06, 0.03): the bisection solves the general ratio.
  const std::vector<double> g = {0.1, 0.06, 0.03};
  const Extrapolation e = richardson(g, sequence(g, 50.0, -400.0, 1.7));
  EXPECT_TRUE(e.observed);
  EXPECT_NEAR(e.order, 1.7, 1e-9);
  EXPECT_NEAR(e.limit, 50.0, 1e-9);
}

TEST(Richardson, TwoLevelsBracketTheTrueLimitForAnyOrderInTheAssumedRange) {
  // Two levels (the default study): the limit is the middle of the extrapolations at the
  // assumed bracket's ends, the error half their spread; for a true order anywhere in the
  // bracket the true limit lies within the estimate ± error (to round-off).
  const std::vector<double> h = {0.08, 0.04};
  for (double p : {kAssumedOrderLow, 1.5, 2.0, kAssumedOrderHigh}) {
    const Extrapolation e = richardson(h, sequence(h, 1000.0, 5000.0, p));
    EXPECT_FALSE(e.observed);
    EXPECT_LE(std::abs(e.limit - 1000.0), e.error * std::abs(e.limit) * (1 + 1e-12)) << p;
  }
  // The numbers: r = 2, last change d = v2 − v1; the ends at d/(2^1.2 − 1) and d/(2^2.7 − 1)
  // beyond v2, so the error is 0.294 |d| / limit.
  const Extrapolation e = richardson(h, {110.0, 100.0});
  const double lo = 100.0 - 10.0 / (std::pow(2.0, 1.2) - 1),
               hi = 100.0 - 10.0 / (std::pow(2.0, 2.7) - 1);
  EXPECT_DOUBLE_EQ(e.limit, 0.5 * (lo + hi));
  EXPECT_DOUBLE_EQ(e.error, 0.5 * (hi - lo) / e.limit);
  EXPECT_NEAR(e.error * e.limit / 10.0, 0.294, 0.001);
}

TEST(Richardson, NonMonotoneThreeLevelsFallBackToTheBracket) {
  // Levels that overshoot (100, 90, 95) have no order: the two finest are extrapolated with the
  // assumed bracket, as with two levels.
  const Extrapolation three = richardson({0.08, 0.04, 0.02}, {100.0, 90.0, 95.0});
  const Extrapolation two = richardson({0.04, 0.02}, {90.0, 95.0});
  EXPECT_FALSE(three.observed);
  EXPECT_DOUBLE_EQ(three.limit, two.limit);
  EXPECT_DOUBLE_EQ(three.error, two.error);
  // A missing level: no limit.
  EXPECT_TRUE(std::isnan(richardson({0.08, 0.04}, {100.0, std::nan("")}).limit));
}

// The convergence reports' three-level rule (solver/core/richardson.hpp): at a constant ratio its
// closed-form order and limit are the study's own on a pure power law (the two rules differ only in
// what they trust, study_cases.hpp); alternating changes have no order there, where the study falls
// back to its bracket.
TEST(Richardson, TheReportsThreeLevelRuleAgreesWithTheStudysOnAPowerLaw) {
  const double r = std::sqrt(2.0);
  const std::vector<double> h = {0.04, 0.04 / r, 0.02};
  for (double p : {1.2, 2.0, 2.7}) {
    const std::vector<double> v = sequence(h, 0.05, 0.8, p);
    const RichardsonRate rate = richardson_rate(v[0], v[1], v[2], r);
    // Round-off: q = r^p from differences of numbers near 0.05 that differ by about 1e-3, so a
    // relative 1e-13 on q; log q / log r carries it to the order, 1e-9 leaves a thousand times
    // that.
    EXPECT_NEAR(rate.order, p, 1e-9) << p;
    EXPECT_NEAR(rate.limit, 0.05, 1e-12) << p;
    EXPECT_NEAR(rate.finest_error, 0.8 * std::pow(0.02, p), 1e-12) << p;
    EXPECT_NEAR(rate.limit, richardson(h, v).limit, 1e-12) << p;
  }
  const RichardsonRate alternating = richardson_rate(100.0, 90.0, 95.0, 2.0);
  EXPECT_TRUE(std::isnan(alternating.order));
  EXPECT_FALSE(richardson({0.08, 0.04, 0.02}, {100.0, 90.0, 95.0}).observed);
}

// The cross-checks' rule (solver/core/richardson.hpp, richardson_estimate): Richardson's limit
// only at an observed order within [kTrustedOrderMin, kTrustedOrderMax]; otherwise the finest
// level, with an error never below its last change.
TEST(Richardson, TheCrossCheckEstimateTakesTheLimitAtAnOrderOfTwo) {
  const double r = std::sqrt(2.0);
  // 300 + 40 h² at h = 1, 1/√2, 1/2: 340, 320, 310, changes 20 then 10 (q = 2, order 2).
  const RichardsonEstimate e = richardson_estimate(340.0, 320.0, 310.0, r);
  EXPECT_TRUE(e.trusted);
  EXPECT_NEAR(e.order, 2.0, 1e-12);
  EXPECT_NEAR(e.value, 300.0, 1e-12);
  EXPECT_NEAR(e.error, 10.0, 1e-12);  // the finest level's distance from the limit
  // And on the power laws of the study's test above, at the ends of the trusted range's interior.
  const std::vector<double> h = {0.04, 0.04 / r, 0.02};
  for (double p : {0.6, 1.0, 2.7, 4.9}) {
    const std::vector<double> v = sequence(h, 0.05, 0.8, p);
    const RichardsonEstimate t = richardson_estimate(v[0], v[1], v[2], r);
    EXPECT_TRUE(t.trusted) << p;
    EXPECT_NEAR(t.value, 0.05, 1e-12) << p;
  }
}

TEST(Richardson, TheCrossCheckEstimateRefusesAStall) {
  // The scan AAA's asperity peak (reports/peers/calculix/README.md): a change of 58 last changes
  // then one, q = 58, "order" log 58 / log √2 = 11.7. Richardson's limit would lie 1/57 of the
  // last change beyond the finest level and claim that as its error: a stall, not a rate.
  const double r = std::sqrt(2.0), d = 0.085, f1 = 63.25, f2 = f1 - 58 * d, f3 = f2 - d;
  const RichardsonRate rate = richardson_rate(f1, f2, f3, r);
  EXPECT_NEAR(rate.order, std::log(58.0) / std::log(r), 1e-9);
  EXPECT_LT(std::abs(rate.finest_error), d / 50);  // what the old rule took as the error
  const RichardsonEstimate e = richardson_estimate(f1, f2, f3, r);
  EXPECT_FALSE(e.trusted);
  EXPECT_NEAR(e.order, rate.order, 1e-12);  // printed, not used
  EXPECT_EQ(e.value, f3);
  EXPECT_GE(e.error, d);
  EXPECT_NEAR(e.error, 3 * d, 1e-12);  // Roache's Fs = 3 at order 2: 3 last changes at √2
  // Just beyond the range's top (order 5.1) the same; just inside (4.9) Richardson's limit.
  for (double p : {4.9, 5.1}) {
    const double q = std::pow(r, p);
    const RichardsonEstimate b = richardson_estimate(10 + q + 1, 11.0, 10.0, r);
    EXPECT_EQ(b.trusted, p < kTrustedOrderMax) << p;
    EXPECT_GE(b.error, b.trusted ? 0.0 : 1.0) << p;
  }
  // Below the range (order 0.3: the limit 8.9 last changes out) also refused.
  const double slow = std::pow(r, 0.3);
  EXPECT_FALSE(richardson_estimate(10 + slow + 1, 11.0, 10.0, r).trusted);
}

TEST(Richardson, TheCrossCheckEstimateRefusesAlternatingAndGrowingChanges) {
  const double r = std::sqrt(2.0);
  // Alternating (−10, then +5): no order; the finest level, ± 3 last changes.
  const RichardsonEstimate alternating = richardson_estimate(100.0, 90.0, 95.0, r);
  EXPECT_FALSE(alternating.trusted);
  EXPECT_TRUE(std::isnan(alternating.order));
  EXPECT_EQ(alternating.value, 95.0);
  EXPECT_NEAR(alternating.error, 15.0, 1e-12);
  // Growing (1, then 2: q = 1/2, order −2): Richardson's formula would extrapolate backwards.
  const RichardsonEstimate growing = richardson_estimate(100.0, 99.0, 97.0, r);
  EXPECT_FALSE(growing.trusted);
  EXPECT_EQ(growing.value, 97.0);
  EXPECT_GE(growing.error, 2.0);
  // At a coarser ratio the GCI band 3/(r² − 1) falls below one last change (r = 3: 0.375); the
  // rule keeps the last change as the floor.
  EXPECT_NEAR(richardson_estimate(100.0, 90.0, 95.0, 3.0).error, 5.0, 1e-12);
  // The study's rule refuses the same range (study_cases.hpp reads these constants).
  EXPECT_EQ(kObservedOrderMin, kTrustedOrderMin);
  EXPECT_EQ(kObservedOrderMax, kTrustedOrderMax);
}

}  // namespace richardson_tests

// The geometry term of the reference (tables/study_cases.hpp, docs/study.md "Guidelines" and "The
// geometry term"): the change of the converged (extrapolated) answer from the next coarser
// resolution that was refined, on hand-made case folders with known values.
namespace geometry_term_tests {

// Two refined levels at h = 0.08 and 0.04 R (sizes halving): the limit is the middle of the
// extrapolations at orders 1.2 and 2.7 (docs/study.md), written out here, not via richardson().
double two_level_limit(double coarse_h, double fine_h) {
  const double d = fine_h - coarse_h;
  return fine_h + 0.5 * d * (1 / (std::pow(2.0, 1.2) - 1) + 1 / (std::pow(2.0, 2.7) - 1));
}

// Peak force of resolution n at refined level l (1: 0.08 R, 2: 0.04 R; 0: coarse): the shape's
// own answer falls with n, the element size's correction is the same fraction at every n.
double peak_of(long n, int level) {
  const double shape = n == 500 ? 1200.0 : n == 1000 ? 1100.0 : 1000.0;
  return level == 0 ? 1.3 * shape : level == 1 ? 1.06 * shape : 1.02 * shape;
}

StudyDef geometry_def(std::vector<long> refined) {
  StudyDef def;
  def.particles = {{.name = "p"}};
  def.resolutions = {500, 1000, 2000};
  def.reference = 2000;
  def.models = {ModelKind::fem};
  def.placements = {Placement::lowest};
  def.refinement.sizes = {0.08, 0.04};
  def.refinement.resolutions = std::move(refined);
  return def;
}

fs::path write_study(const StudyDef& def, const std::string& name) {
  const fs::path dir = scratch(name);
  for (const CaseKey& k : plan_cases(def)) {
    // impulse and duration move with the level too, by other fractions
    const double peak = peak_of(k.resolution, k.level);
    test::write_case(dir, k,
                     {.peak = peak,
                      .impulse = 1e-4 * peak * (1 + 0.01 * k.level),
                      .duration = 1e-4 * (1 + 0.1 * k.level)});
  }
  return dir;
}

TEST(GeometryTerm, ChangeOfTheLimitFromTheNextCoarserRefinedResolution) {
  // Every resolution refined: the reference is the limit at 2000, its geometry term the limit's
  // change from 1000's, |L1000 − L2000| / L2000, and its uncertainty √(d² + g²).
  const StudyDef def = geometry_def({});
  const StudyCases s = load_study_cases(def, write_study(def, "geometry_all"));
  const StudyCases::Reference* r = s.reference("p", Placement::lowest);
  ASSERT_NE(r, nullptr);
  const double l2000 = two_level_limit(peak_of(2000, 1), peak_of(2000, 2));
  const double l1000 = two_level_limit(peak_of(1000, 1), peak_of(1000, 2));
  // 1e-12: the same few operations in another order (round-off only)
  EXPECT_NEAR(r->values.peak, l2000, 1e-12 * l2000);
  EXPECT_EQ(r->geometry_resolution, 1000);
  const double g = std::abs(l1000 - l2000) / l2000;  // 10 %: the shapes' 1100 against 1000
  EXPECT_NEAR(r->geometry.peak, g, 1e-12);
  EXPECT_NEAR(r->geometry.peak, 0.1, 1e-12);  // the fractions of the level cancel
  EXPECT_NEAR(r->uncertainty.peak, std::hypot(r->discretization.peak, g), 1e-15);
  // The sequence at 1000 carries the limit the term compares with.
  EXPECT_NEAR(s.sequence("p", 1000, Placement::lowest)->limit.peak, l1000, 1e-12 * l1000);
}

TEST(GeometryTerm, SkipsACoarserResolutionThatWasNotRefined) {
  // 1000 only coarse: its answer is no converged one, so the term compares with 500's limit.
  const StudyDef def = geometry_def({500, 2000});
  const StudyCases s = load_study_cases(def, write_study(def, "geometry_skip"));
  const StudyCases::Reference* r = s.reference("p", Placement::lowest);
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->geometry_resolution, 500);
  EXPECT_NEAR(r->geometry.peak, 0.2, 1e-12);  // the shapes' 1200 against 1000
  // Only the finest resolution refined (the default study): no geometry term, and the
  // uncertainty is the discretization term alone.
  const StudyDef only = geometry_def({2000});
  const StudyCases t = load_study_cases(only, write_study(only, "geometry_none"));
  const StudyCases::Reference* q = t.reference("p", Placement::lowest);
  ASSERT_NE(q, nullptr);
  EXPECT_EQ(q->geometry_resolution, 0);
  EXPECT_TRUE(std::isnan(q->geometry.peak));
  EXPECT_DOUBLE_EQ(q->uncertainty.peak, q->discretization.peak);
}

TEST(StudySummary, CountsTheMeshingOncePerMeshNotPerRefinedLevel) {
  // Three resolutions, each meshed once (mesh.json's mesh_cpu_seconds N/1000 s) and run at three
  // levels (coarse, 0.08 and 0.04 R) of 1 s each: the meshing is 0.5 + 1 + 2 s, the total 9 + 3.5
  // s (the refined cases read the coarse case's mesh.json; before, it was counted at each level).
  const StudyDef def = geometry_def({});
  const fs::path dir = write_study(def, "summary_meshing");
  for (long n : def.resolutions) {
    const fs::path mesh = dir / "meshes" / "p" / std::to_string(n);
    fs::create_directories(mesh);
    std::ofstream(mesh / "mesh.json")
        << OJson{{"mesh_cpu_seconds", static_cast<double>(n) / 1000}}.dump();
  }
  const OJson summary =
      write_study_summary(load_study_cases(def, dir), {}, OJson(), StudyOutcome{}, dir);
  EXPECT_DOUBLE_EQ(summary["cpu_seconds_by_model"]["meshing"].get<double>(), 3.5);
  EXPECT_DOUBLE_EQ(summary["cpu_seconds_by_model"]["fem"].get<double>(), 9.0);
  EXPECT_DOUBLE_EQ(summary["cpu_seconds_total"].get<double>(), 12.5);
}

}  // namespace geometry_term_tests

}  // namespace
}  // namespace asperity::study::tables
