// The scene key damping_ratio of a deformable body: ξ of its highest element mode, turned into
// the Kelvin–Voigt β = 2ξ/ω_max (fdem::make_world).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "run/run_scene.hpp"
#include "scene/scene.hpp"

namespace asperity::run {
namespace {

namespace fs = std::filesystem;

fs::path particle_scene(const std::string& name, const std::string& model,
                        const std::string& extra) {
  const std::string mesh = std::string(ASPERITY_SOURCE_DIR) + "/data/meshes/particle-seed3-320.off";
  const std::string text = R"({"name": ")" + name + R"(", "duration": 1e-6,
    "materials": {"rock": {"density": 2650, "young": 5e10, "poisson": 0.25}},
    "bodies": [
      {"name": "particle", "material": "rock", "model": ")" +
                           model + R"(", "shape": {"type": "mesh", "file": ")" + mesh +
                           R"(", "faces": 100}, "position": [0, 0, 0.0197])" + extra + R"(},
      {"name": "block", "material": "rock",
       "shape": {"type": "box", "min": [-0.05, -0.05, -0.02], "max": [0.05, 0.05, 0]}}],
    "contact": {"law": "potential"}, "record": {"force_on": "particle"}})";
  const fs::path dir = fs::temp_directory_path() / "asperity_fdem_damping";
  fs::create_directories(dir);
  const fs::path file = dir / (name + ".json");
  std::ofstream(file) << text;
  return file;
}

// With ξ at the highest element mode, the element part of the predicted step is the damped bound
// (2/ω)(√(1+ξ²) − ξ) (Belytschko, Liu & Moran 2000, eq. 6.2.23) of the undamped 2/ω: the ratio
// √(1+ξ²) − ξ to round-off (1e-9), which holds only if β = 2ξ/ω_max at the same ω.
TEST(DampingRatio, ShortensTheElementStepByTheDampedFactor) {
  const RunOptions o{.keep_rows = false};
  const RunResult plain = run_scene(scene::load_scene(particle_scene("plain", "fem", "")), o);
  const double xi = 0.5;
  const RunResult damped =
      run_scene(scene::load_scene(particle_scene("damped", "fem", R"(, "damping_ratio": 0.5)")), o);
  const double ratio =
      damped.summary["dt_element"].get<double>() / plain.summary["dt_element"].get<double>();
  EXPECT_NEAR(ratio, std::sqrt(1 + xi * xi) - xi, 1e-9);
  EXPECT_GT(damped.summary["bodies"][0]["damping"].get<double>(), 0);
}

TEST(DampingRatio, RigidBodyRefusesIt) {
  try {
    scene::load_scene(particle_scene("rigid-damped", "rigid", R"(, "damping_ratio": 0.1)"));
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("damping_ratio: only a moving deformable body"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace asperity::run
