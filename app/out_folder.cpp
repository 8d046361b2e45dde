// Output checks shared by every command that writes (issue 18, class 5; issue 31, classes 3, 9).
#include "app/out_folder.hpp"

#include <limits.h>
#include <sys/statfs.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <string>

#include "solver/core/error.hpp"
#include "solver/io/atomic_file.hpp"

namespace asperity::app {
namespace {
namespace fs = std::filesystem;

[[noreturn]] void bad(const std::string& option, const fs::path& out, const std::string& problem) {
  throw InputError(option + " " + (out.empty() ? std::string("\"\"") : out.string()) + ": " +
                   problem);
}

// File systems of the kernel's own state: creating a folder there fails (EPERM, ENOENT) or,
// worse, writes a kernel setting. From linux/magic.h.
bool virtual_file_system(long type) {
  switch (type) {
    case 0x9fa0:      // proc
    case 0x62656572:  // sysfs
    case 0x27e0eb:    // cgroup
    case 0x63677270:  // cgroup2
    case 0x64626720:  // debugfs
    case 0x74726163:  // tracefs
    case 0x73636673:  // securityfs
    case 0x62656570:  // configfs
    case 0xde5e81e4:  // efivarfs
    case 0xcafe4a11:  // bpf
      return true;
    default:
      return false;
  }
}

// Every component within the file system's name limit, and the whole within PATH_MAX: a
// 300-character component was a raw "File name too long" after the run.
void check_lengths(const std::string& option, const fs::path& out) {
  if (out.native().size() >= PATH_MAX)
    bad(option, out, "longer than " + std::to_string(PATH_MAX - 1) + " characters");
  for (const fs::path& part : out) {
    if (part.native().size() > NAME_MAX) {
      bad(option, out,
          "a component is " + std::to_string(part.native().size()) + " characters, more than the " +
              std::to_string(NAME_MAX) + " a file name may have");
    }
  }
}

// The nearest ancestor of `p` that exists must be a writable folder on a file system that takes
// files.
void check_ancestor(const std::string& option, const fs::path& out, const fs::path& p) {
  std::error_code ec;
  fs::path up = fs::absolute(p, ec);
  if (ec) bad(option, out, "not a usable path (" + ec.message() + ")");
  while (!up.empty() && !fs::exists(fs::symlink_status(up, ec))) {
    if (up == up.parent_path()) break;
    up = up.parent_path();
  }
  if (!fs::is_directory(up, ec)) bad(option, out, up.string() + " is not a folder");
  struct statfs fs_type {};
  if (::statfs(up.c_str(), &fs_type) == 0 && virtual_file_system(fs_type.f_type))
    bad(option, out, up.string() + " is on a virtual file system of the kernel, not for output");
  struct statvfs vfs {};
  if (::statvfs(up.c_str(), &vfs) == 0 && (vfs.f_flag & ST_RDONLY) != 0)
    bad(option, out, up.string() + " is on a read-only file system");
  if (::access(up.c_str(), W_OK | X_OK) != 0) bad(option, out, "cannot write into " + up.string());
}

}  // namespace

void check_out_folder(const fs::path& out, const std::string& option) {
  if (out.empty()) bad(option, out, "must name a folder");
  check_lengths(option, out);
  std::error_code ec;
  const fs::file_status st = fs::status(out, ec);
  if (fs::exists(st) && !fs::is_directory(st)) bad(option, out, "exists and is not a folder");
  check_ancestor(option, out, out);
}

void check_out_file(const fs::path& out, const std::string& option) {
  if (out.empty()) bad(option, out, "must name a file");
  check_lengths(option, out);
  std::error_code ec;
  if (fs::is_directory(fs::status(out, ec))) bad(option, out, "is a folder; give a file name");
  if (const std::string what = io::not_replaceable(out); !what.empty())
    bad(option, out, "is " + what + "; give a regular file or a new name");
  check_ancestor(option, out, out.has_parent_path() ? out.parent_path() : fs::path("."));
}

}  // namespace asperity::app
