// Output-folder checks shared by every command that writes (issue 18, class 5).
#include "app/out_folder.hpp"

#include <unistd.h>

#include <string>

#include "solver/core/error.hpp"

namespace asperity::app {
namespace {
namespace fs = std::filesystem;

[[noreturn]] void bad(const fs::path& out, const std::string& problem) {
  throw InputError("--out " + (out.empty() ? std::string("\"\"") : out.string()) + ": " + problem);
}

// The nearest ancestor of `p` that exists must be a writable folder.
void check_ancestor(const fs::path& out, const fs::path& p) {
  std::error_code ec;
  fs::path up = fs::absolute(p, ec);
  if (ec) bad(out, "not a usable path (" + ec.message() + ")");
  while (!up.empty() && !fs::exists(fs::symlink_status(up, ec))) {
    if (up == up.parent_path()) break;
    up = up.parent_path();
  }
  if (!fs::is_directory(up, ec)) bad(out, up.string() + " is not a folder");
  if (::access(up.c_str(), W_OK | X_OK) != 0) bad(out, "cannot write into " + up.string());
}

}  // namespace

void check_out_folder(const fs::path& out) {
  if (out.empty()) bad(out, "must name a folder");
  std::error_code ec;
  const fs::file_status st = fs::status(out, ec);
  if (fs::exists(st)) {
    if (!fs::is_directory(st)) bad(out, "exists and is not a folder");
    if (::access(out.c_str(), W_OK | X_OK) != 0) bad(out, "folder is not writable");
    return;
  }
  check_ancestor(out, out);
}

void check_out_file(const fs::path& out) {
  if (out.empty()) bad(out, "must name a file");
  std::error_code ec;
  const fs::file_status st = fs::status(out, ec);
  if (fs::is_directory(st)) bad(out, "is a folder; give a file name");
  if (fs::exists(st) && !fs::is_regular_file(st)) bad(out, "exists and is not a regular file");
  check_ancestor(out, out.has_parent_path() ? out.parent_path() : fs::path("."));
}

}  // namespace asperity::app
