// Reading JSON files with messages that name the file, line and column; checked key access.
#pragma once

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/core/vec.hpp"

namespace asperity::io {

using Json = nlohmann::json;

// Limits on any JSON input: no scene, case or study comes near them, and each bounds what a
// hostile file can cost (memory, stack depth in every recursive walk, stderr volume).
inline constexpr std::uintmax_t kMaxJsonBytes = 64u << 20;  // 64 MiB
inline constexpr std::size_t kMaxJsonDepth = 64;            // a scene nests 5 levels, a case 7
inline constexpr std::size_t kEchoChars = 80;               // a rejected value is shown this long

// The bytes of an input file. Throws InputError "FILE: problem" unless FILE is a regular file of at
// most max_bytes (a folder, FIFO or device is refused before it is opened: a FIFO would block and
// /dev/zero never ends).
std::string read_input_file(const std::filesystem::path& file, std::uintmax_t max_bytes);

// Parses JSON text read from FILE. Throws InputError "FILE:LINE:COL: KEY.PATH: invalid JSON: ..."
// on a syntax error, a number beyond a double's range, a duplicate key, nesting deeper than
// kMaxJsonDepth, or a NUL byte.
Json parse_json_text(const std::string& text, const std::filesystem::path& file);

// read_input_file (at most kMaxJsonBytes) then parse_json_text.
Json read_json_file(const std::filesystem::path& file);

// A value as it appears in a message: compact JSON cut to about kEchoChars characters.
std::string echo(const Json& v);

// Closest of `allowed` to `key` by edit distance, or "" when none is close.
std::string closest_key(std::string_view key, std::span<const std::string_view> allowed);
inline std::string closest_key(std::string_view key,
                               std::initializer_list<std::string_view> allowed) {
  return closest_key(key, std::span<const std::string_view>(allowed.begin(), allowed.size()));
}
inline std::string closest_key(std::string_view key, const std::vector<std::string_view>& allowed) {
  return closest_key(key, std::span<const std::string_view>(allowed));
}

// A cursor on one JSON object inside a file: every accessor validates type and range and throws
// InputError "FILE: KEY.PATH: problem (got VALUE)".
class JsonReader {
 public:
  JsonReader(const Json& value, std::filesystem::path file, std::string path);

  const Json& value() const { return value_; }
  const std::string& path() const { return path_; }
  const std::filesystem::path& file() const { return file_; }
  bool has(std::string_view key) const;
  JsonReader child(std::string_view key) const;  // required object or value
  JsonReader at(std::size_t index) const;        // array element

  // Rejects keys not listed, suggesting the closest allowed one.
  void only_keys(std::initializer_list<std::string_view> allowed) const {
    only_keys_in(std::span(allowed.begin(), allowed.size()));
  }
  void only_keys_in(std::span<const std::string_view> allowed) const;  // a key table
  void require_object() const;
  std::size_t require_array() const;  // returns the length

  double number(std::string_view key) const;
  double number_or(std::string_view key, double fallback) const;
  double positive(std::string_view key) const;                 // > 0
  double in_range(std::string_view key, double lo, double hi,  // lo < x ≤ hi or lo ≤ x ≤ hi
                  bool lo_open, bool hi_open) const;
  long long integer(std::string_view key, long long lo, long long hi) const;
  bool boolean_or(std::string_view key, bool fallback) const;
  std::string string(std::string_view key) const;
  Vec3 vec3(std::string_view key) const;
  Vec3 vec3_or(std::string_view key, const Vec3& fallback) const;

  [[noreturn]] void fail(std::string_view key, const std::string& problem) const;

 private:
  std::string key_path(std::string_view key) const;
  const Json& get(std::string_view key) const;
  const Json& value_;
  std::filesystem::path file_;
  std::string path_;
};

}  // namespace asperity::io
