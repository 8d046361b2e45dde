// Where a command writes (`--out`, `--junit`), checked before any work starts, so that a bad one
// is exit 2 with nothing run, not a raw filesystem error after a long run, and so that no output
// ever replaces a device, a FIFO, a socket or a folder (docs/hostile.md, "Outputs"). Every
// command that writes calls these first.
#pragma once

#include <filesystem>
#include <string>

namespace asperity::app {

// Throws InputError "OPTION PATH: problem" when PATH is empty, exists and is not a folder, lies
// under a file, has a component longer than the file system allows, lies on a read-only or
// virtual file system (/proc, /sys), or its nearest existing ancestor is not writable. Creates
// nothing.
void check_out_folder(const std::filesystem::path& out, const std::string& option = "--out");

// The same for an output file (`particle --out FILE`, `--junit FILE`): a regular file (replaced)
// or a new name; never a folder, a device, a FIFO, a socket or a link to one; its folder creatable.
void check_out_file(const std::filesystem::path& out, const std::string& option = "--out");

}  // namespace asperity::app
