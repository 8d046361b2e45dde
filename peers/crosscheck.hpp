// `asperity crosscheck`: one scene in asperity and in each named peer, measured alike, compared.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "solver/scene/scene.hpp"

namespace asperity::peers {

struct CrosscheckOptions {
  std::filesystem::path scene_file;             // a scene, or a validation case (its "scene")
  std::filesystem::path out;                    // DIR: DIR/asperity/, DIR/PEER/, comparison.json
  std::vector<std::string> peers{"yade"};       // adapters' names, in order
  std::map<std::string, std::string> programs;  // peer -> executable, overriding its default
  std::optional<double> max_rel_diff;           // gate peak force, impulse, duration
  std::optional<std::filesystem::path> junit;   // JUnit XML of the gate
  bool only_expressible = false;  // a peer that cannot express the scene is listed with its
                                  // reason in comparison.json ("not_run"), not exit 2 (tables)
  bool cost_only = false;         // the cost table: each code's plain run alone, DIR/cost.json, no
                                  // trace, no comparison (tools/report/peer_cost.py)
  bool quiet = false;
};

// A scene file, or a validation case file (its "scene" object). Throws InputError.
scene::SceneDef load_scene_or_case(const std::filesystem::path& file);

// With cost_only: asperity's run, then each peer's plain run (RunMode::cost) into DIR/PEER/, and
// DIR/cost.json: per code the engine loop's CPU and wall seconds (each code's own clock), the whole
// run's (asperity: loading the scene to writing its outputs; a peer: its process, start to exit,
// from the children's CPU time) and the loop CPU per step and particle.
//
// Exit code: 0 done (and agreed, when gated), 1 a peer failed or a difference exceeded the gate,
// 3 asperity's run went unstable. Throws InputError (exit 2) for bad input, before anything runs
// or is written: an unknown or uninstalled peer, a scene a peer cannot express.
int crosscheck(const CrosscheckOptions& options);

}  // namespace asperity::peers
