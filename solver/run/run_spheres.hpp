// The sphere DEM path of `asperity run` (rigid spheres, planes, boxes).
#pragma once

#include "solver/run/run_result.hpp"
#include "solver/run/step_policy.hpp"
#include "solver/scene/scene.hpp"

namespace asperity::run {

// Same contract as run_scene (summary keys, rows, InputError for a scene it cannot run).
RunResult run_spheres(const scene::SceneDef& scene, const RunOptions& options);

// The step run_spheres would take (world built, not stepped).
StepChoice sphere_step(const scene::SceneDef& scene, const RunOptions& options);

}  // namespace asperity::run
