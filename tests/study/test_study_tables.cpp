// The study's table units on hand-made inputs: the published reference data read from
// data/study/, its refusal of a broken file, and the per-particle classes.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "study/tables/tables.hpp"

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
  const fs::path dir = fs::temp_directory_path() / ("asperity_study_tables_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
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

}  // namespace richardson_tests

}  // namespace
}  // namespace asperity::study::tables
