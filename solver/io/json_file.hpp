// Reading JSON files with messages that name the file, line and column; checked key access.
#pragma once

#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/vec.hpp"

namespace asperity::io {

using Json = nlohmann::json;

// Parses a JSON file. Throws InputError "FILE:LINE:COL: ..." on a syntax error or a missing file.
Json read_json_file(const std::filesystem::path& file);

// Closest of `allowed` to `key` by edit distance, or "" when none is close.
std::string closest_key(std::string_view key, std::initializer_list<std::string_view> allowed);
std::string closest_key(std::string_view key, const std::vector<std::string_view>& allowed);

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
  void only_keys(std::initializer_list<std::string_view> allowed) const;
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
