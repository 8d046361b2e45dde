// Whole-file writes that never leave a half-written file under the final name.
#pragma once

#include <filesystem>
#include <string>

namespace asperity::io {

// Writes `text` to a temporary file beside `file`, then renames it over `file`.
void write_atomically(const std::filesystem::path& file, const std::string& text);

}  // namespace asperity::io
