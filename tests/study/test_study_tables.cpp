// The study's table units on hand-made inputs: the published reference data read from
// data/study/, its refusal of a broken file, and the per-particle classes.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

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

}  // namespace
}  // namespace asperity::study::tables
