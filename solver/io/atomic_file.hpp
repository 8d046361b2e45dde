// Whole-file writes that never leave a half-written file under the final name, and never replace
// or remove anything but a regular file (docs/hostile.md, "Outputs").
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>

namespace asperity::io {

// Writes `text` to a temporary file beside `file`, then renames it over `file`. Throws (and
// replaces nothing) when `file` exists and is not a regular file (a folder, a device, a FIFO, a
// socket, a link to one of those): a rename would put the output in its place.
void write_atomically(const std::filesystem::path& file, const std::string& text);

// The same, the content written by `fill` into the temporary (doubles at full precision).
void write_atomically(const std::filesystem::path& file,
                      const std::function<void(std::ostream&)>& fill);

// What is at `path` if an output may not go there: "" when nothing is there or a regular file
// (or a link to one) is, else what is there ("a folder", "a device", ...).
std::string not_replaceable(const std::filesystem::path& path);

// Removes an earlier run's output file at `path` before a run, so that it cannot be mistaken for
// the new one. Only a regular file (or a link, not its target) goes; anything else there throws
// InputError naming it, and nothing is removed.
void remove_earlier_output(const std::filesystem::path& path);

// Makes `dir` an empty folder for a run's outputs (a peer's scratch and results): creates it when
// absent, else removes what an earlier run left in it. Only regular files, links (never their
// targets) and folders holding only those go. `dir` itself a link, or anything else in it (a
// device, a FIFO, a socket), throws InputError naming it before anything is removed: a link
// followed would empty a folder outside the output folder.
void empty_output_folder(const std::filesystem::path& dir);

}  // namespace asperity::io
