// `orientations: {"random": K}` in a study definition (docs/study.md, "Study file"): each particle
// studied K times as particles of their own, each a rigid rotation of the same surface, the k-th
// rotation independent of K, and the key's bad values refused naming it.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "solver/core/error.hpp"
#include "study/study_def.hpp"
#include "study/study_meshes.hpp"

namespace asperity::study {
namespace {
namespace fs = std::filesystem;

fs::path study_file(const std::string& name, const std::string& extra) {
  const fs::path dir = fs::temp_directory_path() / "asperity_study_orientations";
  fs::create_directories(dir);
  const fs::path file = dir / (name + ".json");
  std::ofstream(file) << R"({"particles": {"meshes": [{"name": "p", "file": ")"
                      << ASPERITY_SOURCE_DIR << R"(/data/meshes/particle-seed3-320.off"}]},
    "resolutions": [100], "models": ["sphere"], "placements": ["lowest"])"
                      << extra << "}";
  return file;
}

// The distances of the vertices from the centroid, sorted: a rotation keeps them.
std::vector<double> radii(const SurfaceMesh& m) {
  std::vector<double> r;
  for (Eigen::Index i = 0; i < m.vertices.cols(); ++i) r.push_back(m.vertices.col(i).norm());
  std::sort(r.begin(), r.end());
  return r;
}

TEST(Orientations, EachIsAParticleOfItsOwnRotatedRigidly) {
  const StudyDef three = load_study(study_file("three", R"(, "orientations": {"random": 3})"));
  ASSERT_EQ(three.particles.size(), 3u);
  EXPECT_EQ(three.particles[0].name, "p-o1");
  EXPECT_EQ(three.particles[2].name, "p-o3");
  EXPECT_EQ(three.particles[2].orientation, 2);
  const SurfaceMesh a = particle_source(three, 0), b = particle_source(three, 1);
  // Another rotation: the vertices move (by a fraction of the size, far above round-off) ...
  EXPECT_GT((a.vertices - b.vertices).norm(), 1e-3 * a.vertices.norm());
  // ... rigidly: every distance from the centroid kept to round-off (1e-12 of the radius).
  const std::vector<double> ra = radii(a), rb = radii(b);
  for (std::size_t i = 0; i < ra.size(); ++i) EXPECT_NEAR(ra[i], rb[i], 1e-12 * ra.back());
  // The k-th rotation does not depend on K: a study at 5 orientations repeats the first 3.
  const StudyDef five = load_study(study_file("five", R"(, "orientations": {"random": 5})"));
  EXPECT_EQ(particle_source(five, 1).vertices, b.vertices);
}

TEST(Orientations, BadValuesAreRefusedNamingTheKey) {
  for (const std::string extra : {R"(, "orientations": {"random": 0})",
                                  R"(, "orientations": {"random": 2}, "orientation": "random")",
                                  R"(, "orientations": {"every": 2})"}) {
    try {
      load_study(study_file("bad", extra));
      ADD_FAILURE() << "accepted" << extra;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("orientations"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace asperity::study
