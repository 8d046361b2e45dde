// The rule for a name from the input that becomes a file or folder under an output folder (a
// validation case, a particle of a set or of a study): one rule for every command, since a name
// "../../escape" or "/abs/path" would write outside --out (docs/hostile.md, "Names").
#pragma once

#include <string>

namespace asperity::io {

// At most this many bytes: a file name may have 255 (NAME_MAX), and a suffix such as ".off" or
// ".partial-PID" is added to some.
inline constexpr std::size_t kMaxPlainName = 200;

// "" when `name` is a plain name, else what is wrong with it.
inline std::string plain_name_problem(const std::string& name) {
  if (name.empty()) return "must not be empty";
  if (name.size() > kMaxPlainName)
    return "longer than " + std::to_string(kMaxPlainName) + " characters (got " +
           std::to_string(name.size()) + ")";
  if (name == "." || name == "..") return "must not be \"" + name + "\" (it names a folder)";
  for (const char c : name) {
    if (c == '/' || c == '\\')
      return "must not contain a path separator (it names a file or folder under --out)";
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      return "must not contain control characters";
  }
  return "";
}

}  // namespace asperity::io
