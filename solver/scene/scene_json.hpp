// Scene parsing from a JSON value already in memory (validation cases embed their scene).
#pragma once

#include <filesystem>
#include <string>

#include "solver/io/json_file.hpp"
#include "solver/scene/scene.hpp"

namespace asperity::scene {

// prefix: the key path of the scene inside its file ("" at the top, "scene" inside a case).
SceneDef parse_scene(const io::Json& json, const std::filesystem::path& file,
                     const std::string& prefix);

}  // namespace asperity::scene
