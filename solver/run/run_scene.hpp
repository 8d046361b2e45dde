// `asperity run`: a scene dispatched to its model's runner (run_spheres, run_fdem), each through
// the one step policy (run/step_policy.hpp), time loop (run/time_loop.hpp) and summary core
// (run/summary.hpp); and the contract's output files.
#pragma once

#include <filesystem>

#include "solver/run/run_result.hpp"
#include "solver/run/step_policy.hpp"
#include "solver/scene/scene.hpp"

namespace asperity::run {

// Throws InputError for a scene the solver cannot run (bad geometry, unsafe dt, ...).
RunResult run_scene(const scene::SceneDef& scene, const RunOptions& options = {});

// The step `asperity run` would take for this scene ("auto" resolved), without running it. Builds
// the world once (mesh bodies are read and meshed).
StepChoice predicted_step(const scene::SceneDef& scene, const RunOptions& options = {});

// Writes summary.json, force.csv and energy.csv into `out` (each via a temporary file and a
// rename, summary.json last); an unstable run writes summary.json only.
void write_outputs(const RunResult& result, const std::filesystem::path& out);

}  // namespace asperity::run
