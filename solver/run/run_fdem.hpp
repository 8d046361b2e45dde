// The FEM/DEM path of `asperity run`: scenes with mesh bodies (model "rigid" or "fem") against
// each other and against fixed boxes and planes, in Munjiza's potential contact.
#pragma once

#include "run/run_result.hpp"
#include "run/step_policy.hpp"
#include "scene/scene.hpp"

namespace asperity::run {

// True when the scene has a mesh body or asks for the potential law: run_fdem runs it.
bool is_fdem_scene(const scene::SceneDef& scene);

// Same contract as run_scene (summary keys, rows, InputError for a scene it cannot run).
RunResult run_fdem(const scene::SceneDef& scene, const RunOptions& options);

// The step run_fdem would take (world built, not stepped).
StepChoice fdem_step(const scene::SceneDef& scene, const RunOptions& options);

}  // namespace asperity::run
