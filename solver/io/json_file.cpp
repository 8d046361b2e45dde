// Checked JSON access for input files (scenes, validation cases, studies).
#include "io/json_file.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/error.hpp"

namespace asperity::io {

Json read_json_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot open file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  try {
    return Json::parse(text);
  } catch (const Json::parse_error& e) {
    // nlohmann reports a byte offset; users want line and column.
    const std::size_t at = std::min<std::size_t>(e.byte == 0 ? 0 : e.byte - 1, text.size());
    std::size_t line = 1, col = 1;
    for (std::size_t i = 0; i < at; ++i) {
      if (text[i] == '\n') {
        ++line;
        col = 1;
      } else {
        ++col;
      }
    }
    std::string what = e.what();
    if (auto p = what.find("parse error"); p != std::string::npos) what = what.substr(p);
    throw InputError(file.string() + ":" + std::to_string(line) + ":" + std::to_string(col) +
                     ": invalid JSON: " + what);
  }
}

std::string closest_key(std::string_view key, std::initializer_list<std::string_view> allowed) {
  return closest_key(key, std::vector<std::string_view>(allowed));
}

std::string closest_key(std::string_view key, const std::vector<std::string_view>& allowed) {
  std::string best;
  std::size_t best_d = 3;  // suggest only near misses: at most two edits
  for (std::string_view cand : allowed) {
    std::vector<std::size_t> row(cand.size() + 1);
    for (std::size_t j = 0; j <= cand.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= key.size(); ++i) {
      std::size_t diag = row[0];
      row[0] = i;
      for (std::size_t j = 1; j <= cand.size(); ++j) {
        const std::size_t up = row[j];
        row[j] = std::min({row[j] + 1, row[j - 1] + 1,
                           diag + (std::tolower(key[i - 1]) == std::tolower(cand[j - 1]) ? 0 : 1)});
        diag = up;
      }
    }
    if (row[cand.size()] < best_d) {
      best_d = row[cand.size()];
      best = cand;
    }
  }
  return best;
}

JsonReader::JsonReader(const Json& value, std::filesystem::path file, std::string path)
    : value_(value), file_(std::move(file)), path_(std::move(path)) {}

std::string JsonReader::key_path(std::string_view key) const {
  if (path_.empty()) return std::string(key);
  if (key.empty()) return path_;
  return path_ + "." + std::string(key);
}

void JsonReader::fail(std::string_view key, const std::string& problem) const {
  const std::string where = key_path(key);
  throw InputError(file_.string() + ": " + (where.empty() ? "" : where + ": ") + problem);
}

bool JsonReader::has(std::string_view key) const {
  return value_.is_object() && value_.contains(std::string(key));
}

const Json& JsonReader::get(std::string_view key) const {
  require_object();
  auto it = value_.find(std::string(key));
  if (it == value_.end()) fail(key, "missing required key");
  return *it;
}

JsonReader JsonReader::child(std::string_view key) const {
  return JsonReader(get(key), file_, key_path(key));
}

JsonReader JsonReader::at(std::size_t index) const {
  return JsonReader(value_.at(index), file_, path_ + "[" + std::to_string(index) + "]");
}

void JsonReader::require_object() const {
  if (!value_.is_object()) fail("", "must be an object (got " + value_.dump() + ")");
}

std::size_t JsonReader::require_array() const {
  if (!value_.is_array()) fail("", "must be an array (got " + value_.dump() + ")");
  return value_.size();
}

void JsonReader::only_keys(std::initializer_list<std::string_view> allowed) const {
  require_object();
  for (const auto& [k, v] : value_.items()) {
    if (std::find(allowed.begin(), allowed.end(), k) != allowed.end()) continue;
    const std::string near = closest_key(k, allowed);
    fail(k, near.empty() ? "unknown key" : "unknown key (did you mean \"" + near + "\"?)");
  }
}

double JsonReader::number(std::string_view key) const {
  const Json& v = get(key);
  if (!v.is_number()) fail(key, "must be a number (got " + v.dump() + ")");
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail(key, "must be finite (got " + v.dump() + ")");
  return x;
}

double JsonReader::number_or(std::string_view key, double fallback) const {
  return has(key) ? number(key) : fallback;
}

double JsonReader::positive(std::string_view key) const {
  const double x = number(key);
  if (!(x > 0)) fail(key, "must be > 0 (got " + get(key).dump() + ")");
  return x;
}

double JsonReader::in_range(std::string_view key, double lo, double hi, bool lo_open,
                            bool hi_open) const {
  const double x = number(key);
  const bool ok = (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
  if (!ok) {
    std::ostringstream r;
    r << "must lie in " << (lo_open ? "(" : "[") << lo << ", " << hi << (hi_open ? ")" : "]")
      << " (got " << get(key).dump() << ")";
    fail(key, r.str());
  }
  return x;
}

long long JsonReader::integer(std::string_view key, long long lo, long long hi) const {
  const Json& v = get(key);
  if (!v.is_number_integer()) fail(key, "must be an integer (got " + v.dump() + ")");
  const long long x = v.get<long long>();
  if (x < lo || x > hi) {
    fail(key, "must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " +
                  v.dump() + ")");
  }
  return x;
}

bool JsonReader::boolean_or(std::string_view key, bool fallback) const {
  if (!has(key)) return fallback;
  const Json& v = get(key);
  if (!v.is_boolean()) fail(key, "must be true or false (got " + v.dump() + ")");
  return v.get<bool>();
}

std::string JsonReader::string(std::string_view key) const {
  const Json& v = get(key);
  if (!v.is_string()) fail(key, "must be a string (got " + v.dump() + ")");
  return v.get<std::string>();
}

Vec3 JsonReader::vec3(std::string_view key) const {
  const Json& v = get(key);
  if (!v.is_array() || v.size() != 3 ||
      !std::all_of(v.begin(), v.end(), [](const Json& x) { return x.is_number(); })) {
    fail(key, "must be an array of 3 numbers (got " + v.dump() + ")");
  }
  Vec3 out(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
  if (!out.allFinite()) fail(key, "must be finite (got " + v.dump() + ")");
  return out;
}

Vec3 JsonReader::vec3_or(std::string_view key, const Vec3& fallback) const {
  return has(key) ? vec3(key) : fallback;
}

}  // namespace asperity::io
