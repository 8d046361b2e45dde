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
// The CPU seconds that the meshes this thread took from the process's prepared meshes (made for
// an earlier scene with the same file and meshing keys, instead of making them again) cost the
// thread that made them, summed over the thread's life. A caller that times a scene by its
// thread's CPU adds this one's change across the call: the scene then costs what it would alone,
// whichever scene made the mesh first (the study's cases, study_run.cpp).
double kept_mesh_cpu_seconds();

// The step run_fdem would take (world built, not stepped).
StepChoice fdem_step(const scene::SceneDef& scene, const RunOptions& options);

}  // namespace asperity::run
