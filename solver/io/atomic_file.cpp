// Temporary file plus rename: readers see the old file or the new one, never a partial one.
#include "solver/io/atomic_file.hpp"

#include <unistd.h>

#include <fstream>
#include <limits>
#include <stdexcept>
#include <system_error>

#include "solver/core/interrupt.hpp"

namespace asperity::io {

void write_atomically(const std::filesystem::path& file,
                      const std::function<void(std::ostream&)>& fill) {
  const std::filesystem::path tmp = file.string() + ".partial-" + std::to_string(::getpid());
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

}  // namespace asperity::io
