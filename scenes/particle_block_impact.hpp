// The fdem run tests' scene: a generated rock particle dropped onto a fixed block, run whole
// (run_scene). Shared by test_runaway_penetration.cpp and test_prepared_meshes.cpp.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include "solver/run/run_scene.hpp"
#include "solver/scene/scene.hpp"

namespace asperity::run {

// A generated rock particle (100 triangles, TetGen tetrahedra, about 20 mm across) 0.2 mm above a
// fixed block whose top is z = 0, falling at `speed`; `penalty` in Pa (0: the default α E); the
// block (one cell of six tetrahedra) 0.1 m wide and 0.02 m deep, or 1 m wide and deep when
// `deep`.
inline RunResult impact(const std::string& name, const std::string& model, double speed,
                        double penalty, bool deep, double duration, const std::string& extra = "") {
  const std::string lo = deep ? "-0.5, -0.5, -1" : "-0.05, -0.05, -0.02",
                    hi = deep ? "0.5, 0.5, 0" : "0.05, 0.05, 0";
  const std::string mesh = std::string(ASPERITY_SOURCE_DIR) + "/data/meshes/particle-seed3-320.off";
  const std::string contact =
      penalty > 0 ? R"({"law": "potential", "penalty": )" + std::to_string(penalty) + "}"
                  : R"({"law": "potential"})";
  const std::string text = R"({"name": ")" + name + R"(", "gravity": [0, 0, -9.81], "duration": )" +
                           std::to_string(duration) + extra + R"(,
    "materials": {"rock": {"density": 2650, "young": 5e10, "poisson": 0.25,
                         "friction": 0, "restitution": 1}},
    "bodies": [
      {"name": "particle", "material": "rock", "model": ")" +
                           model + R"(",
       "shape": {"type": "mesh", "file": ")" +
                           mesh +
                           R"(", "faces": 100},
       "position": [0, 0, 0.0197], "velocity": [0, 0, )" +
                           std::to_string(-speed) + R"(]},
      {"name": "block", "material": "rock",
       "shape": {"type": "box", "min": [)" +
                           lo + R"(], "max": [)" + hi + R"(]}}],
    "contact": )" + contact +
                           R"(,
    "record": {"force_on": "particle", "every": 100}})";
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "asperity_fdem_impact";
  std::filesystem::create_directories(dir);
  const std::filesystem::path file = dir / (name + ".json");
  std::ofstream(file) << text;
  return run_scene(scene::load_scene(file), {.keep_rows = false});
}

}  // namespace asperity::run
