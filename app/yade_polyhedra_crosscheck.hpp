// The YADE Polyhedra cross-check of rigid mesh bodies (app/yade_polyhedra_crosscheck.cpp).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace asperity::app {

int yade_polyhedra_crosscheck(const std::filesystem::path& scene_file,
                              const std::filesystem::path& out, const std::string& yade,
                              const std::filesystem::path& script,
                              std::optional<double> max_rel_diff, bool quiet);

}  // namespace asperity::app
