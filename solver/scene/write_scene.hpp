// A scene written as the contract's JSON (docs/scenes.md): what a builder of scenes in code (the
// study's cases) writes as scene.json, and what load_scene reads back to the same SceneDef.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include "solver/scene/scene.hpp"

namespace asperity::scene {

// The scene's keys in the contract's order (scene_keys.hpp), each key that holds its default left
// out (gravity, dt, record.force_on and record.every always written; a mesh body's model always).
// Mesh files are written relative to `folder`, the folder the scene file is written into.
nlohmann::ordered_json scene_json(const SceneDef& scene, const std::filesystem::path& folder);

}  // namespace asperity::scene
