// The FEM/DEM path of `asperity run`: scenes with mesh bodies (model "rigid" or "fem") against
// each other and against fixed boxes and planes, in Munjiza's potential contact or, for rigid
// bodies, a volume law.
#pragma once

#include <vector>

#include "solver/core/mesh.hpp"
#include "solver/run/run_result.hpp"
#include "solver/run/step_policy.hpp"
#include "solver/scene/scene.hpp"

namespace asperity::run {

// True when the scene has a mesh body or asks for the potential law: run_fdem runs it.
bool is_fdem_scene(const scene::SceneDef& scene);

// Same contract as run_scene (summary keys, rows, InputError for a scene it cannot run).
RunResult run_fdem(const scene::SceneDef& scene, const RunOptions& options);

// The tetrahedral mesh each scene body collides with in run_fdem, in the world frame (a mesh body
// through the geometry pipeline and placed at its position, a box as its block, a plane as the
// fixed slab under it), by scene body index: what a peer's translator must reproduce.
std::vector<TetMesh> collision_meshes(const scene::SceneDef& scene);

// The step run_fdem would take (world built, not stepped).
StepChoice fdem_step(const scene::SceneDef& scene, const RunOptions& options);

}  // namespace asperity::run
