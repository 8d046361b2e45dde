// Whole-file writes that never leave a half-written file under the final name.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>

namespace asperity::io {

// Writes `text` to a temporary file beside `file`, then renames it over `file`.
void write_atomically(const std::filesystem::path& file, const std::string& text);

// The same, the content written by `fill` into the temporary (doubles at full precision).
void write_atomically(const std::filesystem::path& file,
                      const std::function<void(std::ostream&)>& fill);

}  // namespace asperity::io
