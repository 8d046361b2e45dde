// The meshes a process keeps (run_fdem.cpp, PreparedMeshes): a scene that takes a mesh an earlier
// scene made is charged what making it cost (kept_mesh_cpu_seconds), so that a study case costs
// the same whichever case of its mesh ran first.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "core/clock.hpp"
#include "run/run_fdem.hpp"
#include "run/run_scene.hpp"
#include "scene/scene.hpp"

namespace asperity::run {
namespace {

namespace fs = std::filesystem;

// The generated 100-triangle rock particle, 0.2 mm above a fixed block, for a few steps.
RunResult drop(const std::string& name, const std::string& model, double speed) {
  const std::string mesh = std::string(ASPERITY_SOURCE_DIR) + "/data/meshes/particle-seed3-320.off";
  const std::string text = R"({"name": ")" + name +
                           R"(", "gravity": [0, 0, -9.81], "duration": 2e-5,
    "materials": {"rock": {"density": 2650, "young": 5e10, "poisson": 0.25, "friction": 0}},
    "bodies": [
      {"name": "particle", "material": "rock", "model": ")" +
                           model + R"(",
       "shape": {"type": "mesh", "file": ")" +
                           mesh + R"(", "faces": 100},
       "position": [0, 0, 0.0197], "velocity": [0, 0, )" +
                           std::to_string(-speed) + R"(]},
      {"name": "block", "material": "rock",
       "shape": {"type": "box", "min": [-0.05, -0.05, -0.02], "max": [0.05, 0.05, 0]}}],
    "contact": {"law": "potential"}, "record": {"force_on": "particle", "every": 10}})";
  const fs::path dir = fs::temp_directory_path() / "asperity_prepared_meshes";
  fs::create_directories(dir);
  const fs::path file = dir / (name + ".json");
  std::ofstream(file) << text;
  return run_scene(scene::load_scene(file), {.keep_rows = false});
}

// The first rigid scene makes the mesh (nothing charged); a second rigid scene of the same file
// and keys takes it and is charged more than nothing and no more than the first scene's whole
// CPU (its making is a part of that); a fem scene of the same file makes its own (a deformable
// body's mesh is another key: the mesher's step repair), nothing charged.
TEST(PreparedMeshes, ATakenMeshIsChargedWhatMakingItCost) {
  const double k0 = kept_mesh_cpu_seconds();
  const double c0 = thread_cpu_seconds();
  drop("first", "rigid", 1.0);
  const double first_cpu = thread_cpu_seconds() - c0;
  const double k1 = kept_mesh_cpu_seconds();
  EXPECT_EQ(k1, k0);
  drop("second", "rigid", 2.0);
  const double k2 = kept_mesh_cpu_seconds();
  EXPECT_GT(k2 - k1, 0.0);
  EXPECT_LE(k2 - k1, first_cpu);
  drop("deformable", "fem", 1.0);
  EXPECT_EQ(kept_mesh_cpu_seconds(), k2);
}

}  // namespace
}  // namespace asperity::run
