// Temporary file plus rename: readers see the old file or the new one, never a partial one. The
// rename replaces whatever has the final name, so the final name is checked first: run as root,
// `--junit /dev/null` once replaced the system's /dev/null device with a regular file.
#include "solver/io/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <system_error>

#include "solver/core/error.hpp"
#include "solver/core/interrupt.hpp"

namespace asperity::io {
namespace {

std::string kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Creates `tmp` as a new, empty regular file of this process (O_EXCL: never one that is there,
// O_NOFOLLOW: never through a link), so that only what this process made is ever removed.
void create_own(const std::filesystem::path& tmp) {
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (fd < 0) {
    throw std::runtime_error(tmp.string() + ": cannot create (" +
                             std::error_code(errno, std::generic_category()).message() + ")");
  }
  ::close(fd);
}

}  // namespace

std::string not_replaceable(const std::filesystem::path& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return "";  // nothing there (or unreachable: open says)
  if (S_ISREG(st.st_mode)) return "";
  if (S_ISLNK(st.st_mode)) {
    // A link is replaced by the output (its target untouched); a link to a device or a folder
    // says the user meant the target, which is refused like the target itself.
    if (::stat(path.c_str(), &st) != 0 || S_ISREG(st.st_mode)) return "";
    return "a link to " + kind_of(st.st_mode);
  }
  return kind_of(st.st_mode);
}

void write_atomically(const std::filesystem::path& file,
                      const std::function<void(std::ostream&)>& fill) {
  if (const std::string what = not_replaceable(file); !what.empty())
    throw std::runtime_error(file.string() + ": is " + what + "; not replaced by an output file");
  const std::filesystem::path tmp = file.string() + ".partial-" + std::to_string(::getpid());
  create_own(tmp);
  // The temporary goes whatever happens: a failed write (disk full), an exception in `fill` or
  // an interrupt must not leave a *.partial-PID beside complete-looking files.
  const RemoveOnInterrupt guard(tmp);
  try {
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      if (!out) throw std::runtime_error(tmp.string() + ": cannot write");
      out.precision(std::numeric_limits<double>::max_digits10);
      fill(out);
      out.flush();
      if (!out) throw std::runtime_error(tmp.string() + ": write failed");
    }
    // Checked again just before the rename: the run may have been long.
    if (const std::string what = not_replaceable(file); !what.empty())
      throw std::runtime_error(file.string() + ": is " + what + "; not replaced by an output file");
    std::filesystem::rename(tmp, file);
  } catch (...) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw;
  }
}

void write_atomically(const std::filesystem::path& file, const std::string& text) {
  write_atomically(file, [&](std::ostream& out) { out << text; });
}

void remove_earlier_output(const std::filesystem::path& path) {
  if (const std::string what = not_replaceable(path); !what.empty()) {
    throw InputError(path.string() + ": is " + what +
                     " where an output file goes; asperity neither replaces nor removes it");
  }
  std::error_code ec;
  std::filesystem::remove(path, ec);
}

namespace {

// The first entry under `dir` (a real folder) that empty_output_folder may not remove, or "".
std::string first_unremovable(const std::filesystem::path& dir) {
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    struct stat st {};
    if (::lstat(e.path().c_str(), &st) != 0) continue;  // gone meanwhile
    if (S_ISREG(st.st_mode) || S_ISLNK(st.st_mode)) continue;
    if (S_ISDIR(st.st_mode)) {
      if (std::string what = first_unremovable(e.path()); !what.empty()) return what;
      continue;
    }
    return e.path().string() + ": is " + kind_of(st.st_mode);
  }
  return "";
}

}  // namespace

void empty_output_folder(const std::filesystem::path& dir) {
  struct stat st {};
  if (::lstat(dir.c_str(), &st) != 0) {
    std::filesystem::create_directories(dir);
    return;
  }
  if (S_ISLNK(st.st_mode))
    throw InputError(dir.string() + ": is a link where an output folder goes; asperity neither " +
                     "follows nor empties it");
  if (!S_ISDIR(st.st_mode))
    throw InputError(dir.string() + ": is " + kind_of(st.st_mode) +
                     " where an output folder goes; asperity neither replaces nor removes it");
  if (const std::string what = first_unremovable(dir); !what.empty())
    throw InputError(what + " in an output folder asperity would empty; nothing was removed");
  // remove_all removes a link, never what it points to.
  for (const auto& e : std::filesystem::directory_iterator(dir))
    std::filesystem::remove_all(e.path());
}

}  // namespace asperity::io
