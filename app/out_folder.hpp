// The output folder (`--out`) checked before any work starts, so that a bad one is exit 2 with
// nothing run, not a raw filesystem error after a long run.
#pragma once

#include <filesystem>

namespace asperity::app {

// Throws InputError "--out PATH: problem" when PATH is empty, exists and is not a folder, lies
// under a file, or its nearest existing ancestor is not writable. Creates nothing.
void check_out_folder(const std::filesystem::path& out);

// The same for an output file (`particle --out FILE`): not a folder, its folder creatable.
void check_out_file(const std::filesystem::path& out);

}  // namespace asperity::app
