// The scene key damping_ratio of a deformable body: ξ of its highest element mode, turned into
// the Kelvin–Voigt β = 2ξ/ω_max (fdem::make_world).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "solver/core/error.hpp"
#include "solver/run/run_scene.hpp"
#include "solver/scene/scene.hpp"

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

// Issue 11, item 4: damping the highest element modes (ξ = 0.1 there, ξ ω/ω_max below: the
// contact's own modes are far below ω_max) must leave the impact itself alone. A 250-triangle
// drop at 2 m/s (no test tunes on it; the stability gate and the other tests use 100 triangles):
// impulse and contact duration within 0.5 % of the undamped run (the issue's bound; measured
// −0.02 % and +0.14 %), while the damping does dissipate (restitution lower, so the test sees
// the damping at all). The ringing is not what it removes: raw over filtered peak stays 0.33 %,
// at modes far below ω_max.
TEST(DampingRatio, LeavesImpulseAndDurationWithinHalfAPercent) {
  auto drop = [](const std::string& name, const std::string& extra) {
    const std::string mesh =
        std::string(ASPERITY_SOURCE_DIR) + "/data/meshes/particle-seed3-320.off";
    const std::string text = R"({"name": ")" + name + R"(", "duration": 5e-4,
      "materials": {"rock": {"density": 2650, "young": 5e10, "poisson": 0.25}},
      "bodies": [
        {"name": "rock", "material": "rock", "model": "fem", "shape": {"type": "mesh",
         "file": ")" + mesh + R"(", "faces": 250}, "position": [0, 0, 0.0196],
         "velocity": [0, 0, -2])" +
                             extra + R"(},
        {"name": "slab", "material": "rock",
         "shape": {"type": "box", "min": [-0.05, -0.05, -0.02], "max": [0.05, 0.05, 0]}}],
      "contact": {"law": "potential"},
      "record": {"force_on": "rock", "end_after_separation": 2e-5}})";
    const fs::path dir = fs::temp_directory_path() / "asperity_fdem_damping";
    fs::create_directories(dir);
    const fs::path file = dir / (name + ".json");
    std::ofstream(file) << text;
    return run_scene(scene::load_scene(file), RunOptions{.keep_rows = false}).summary;
  };
  const auto plain = drop("drop-plain", "");
  const auto damped = drop("drop-damped", R"(, "damping_ratio": 0.1)");
  ASSERT_EQ(plain["status"], "ok");
  ASSERT_EQ(damped["status"], "ok");
  const auto rel = [&](const char* key) {
    return damped[key].get<double>() / plain[key].get<double>() - 1;
  };
  EXPECT_LT(std::abs(rel("impulse")), 0.005);
  EXPECT_LT(std::abs(rel("contact_duration")), 0.005);
  EXPECT_LT(damped["restitution"].get<double>(), plain["restitution"].get<double>());
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
