// Checked JSON access for input files (scenes, validation cases, studies).
#include "solver/io/json_file.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <vector>

#include "solver/core/error.hpp"

namespace asperity::io {
namespace {

// Line and column (1-based) of a byte offset, for messages users can jump to.
std::string line_col(const std::string& text, std::size_t offset) {
  const std::size_t at = std::min(offset, text.size());
  std::size_t line = 1, col = 1;
  for (std::size_t i = 0; i < at; ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return std::to_string(line) + ":" + std::to_string(col);
}

// nlohmann's DOM builder behind a SAX layer that knows where it is: it tracks the key path (for
// messages naming the key of a bad number), refuses nesting deeper than kMaxJsonDepth (an input
// of 100,000 nested arrays is an attack, not a scene; the parser itself is iterative but every
// consumer that walks or prints the tree recurses) and refuses duplicate keys (the DOM would keep
// the last one silently).
class CheckedSax {
 public:
  using Dom = nlohmann::detail::json_sax_dom_parser<Json>;
  explicit CheckedSax(Json& root) : dom_(root, false) {}

  bool null() { return value() && dom_.null(); }
  bool boolean(bool v) { return value() && dom_.boolean(v); }
  bool number_integer(Json::number_integer_t v) { return value() && dom_.number_integer(v); }
  bool number_unsigned(Json::number_unsigned_t v) { return value() && dom_.number_unsigned(v); }
  bool number_float(Json::number_float_t v, const std::string& s) {
    return value() && dom_.number_float(v, s);
  }
  bool string(std::string& v) { return value() && dom_.string(v); }
  bool binary(Json::binary_t& v) { return value() && dom_.binary(v); }
  bool start_object(std::size_t n) { return open(false) && dom_.start_object(n); }
  bool start_array(std::size_t n) { return open(true) && dom_.start_array(n); }
  bool end_object() { return close() && dom_.end_object(); }
  bool end_array() { return close() && dom_.end_array(); }
  bool key(std::string& k) {
    Frame& f = frames_.back();
    if (!f.keys.insert(k).second) {
      f.key = k;
      problem_ = "duplicate key";
      return false;
    }
    f.key = k;
    return dom_.key(k);
  }
  template <class Exception>
  bool parse_error(std::size_t position, const std::string& /*token*/, const Exception& ex) {
    position_ = position;
    problem_ = ex.what();
    // "[json.exception.parse_error.101] parse error at line 1, column 5: ..." → from "parse error"
    // on; a number overflow (out_of_range.406) says "number overflow parsing '1e400'".
    for (const char* from : {"parse error", "number overflow"}) {
      if (auto p = problem_.find(from); p != std::string::npos) {
        problem_ = problem_.substr(p);
        break;
      }
    }
    if (problem_.rfind("number overflow", 0) == 0) problem_ += " (beyond the range of a double)";
    return false;
  }

  const std::string& problem() const { return problem_; }
  std::size_t position() const { return position_; }
  bool has_position() const { return position_ != std::string::npos; }

  // The key path of the value being read: "bodies[0].shape.radius".
  std::string path() const {
    std::string p;
    for (std::size_t i = 0; i < frames_.size(); ++i) {
      const Frame& f = frames_[i];
      if (f.array) {
        // Inner frames have counted the element they are inside; the innermost has not yet
        // counted the element being read.
        const std::size_t index = i + 1 < frames_.size() ? f.count - 1 : f.count;
        p += "[" + std::to_string(index) + "]";
      } else if (!f.key.empty() || f.count > 0) {
        p += (p.empty() ? "" : ".") + f.key;
      }
    }
    return p;
  }

 private:
  struct Frame {
    bool array;
    std::size_t count = 0;
    std::string key;
    std::set<std::string> keys;
  };
  bool value() {
    if (!frames_.empty()) ++frames_.back().count;
    return true;
  }
  bool open(bool array) {
    if (frames_.size() >= kMaxJsonDepth) {
      problem_ = "nested deeper than " + std::to_string(kMaxJsonDepth) + " levels";
      return false;
    }
    value();
    frames_.push_back(Frame{.array = array});
    return true;
  }
  bool close() {
    frames_.pop_back();
    return true;
  }
  Dom dom_;
  std::vector<Frame> frames_;
  std::string problem_;
  std::size_t position_ = std::string::npos;
};

}  // namespace

std::string read_input_file(const std::filesystem::path& file, std::uintmax_t max_bytes) {
  // stat, not open: opening a FIFO blocks until a writer comes, and /dev/zero never ends.
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) throw InputError(file.string() + ": cannot open file");
  if (S_ISDIR(st.st_mode)) throw InputError(file.string() + ": is a folder, not a file");
  if (!S_ISREG(st.st_mode)) {
    throw InputError(file.string() + ": not a regular file (a device, FIFO or socket)");
  }
  const auto size = static_cast<std::uintmax_t>(st.st_size);
  if (size > max_bytes) {
    throw InputError(file.string() + ": " + std::to_string(size) + " bytes, more than the " +
                     std::to_string(max_bytes >> 20) + " MiB this input may have");
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot open file");
  // Read at most the cap even if the file grows while we read.
  std::string text(static_cast<std::size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  text.resize(static_cast<std::size_t>(in.gcount()));
  return text;
}

Json parse_json_text(const std::string& text, const std::filesystem::path& file) {
  if (text.empty()) throw InputError(file.string() + ": empty file (0 bytes)");
  if (const std::size_t nul = text.find('\0'); nul != std::string::npos) {
    // nlohmann stops at a NUL and reports "unexpected end of input", which misleads.
    throw InputError(file.string() + ":" + line_col(text, nul) +
                     ": invalid JSON: a NUL byte (binary content, not a JSON text)");
  }
  Json out;
  CheckedSax sax(out);
  bool ok = false;
  try {
    ok = Json::sax_parse(text, &sax);
  } catch (const Json::exception& e) {
    throw InputError(file.string() + ": invalid JSON: " + e.what());
  }
  if (ok) return out;
  const std::string where = sax.path();
  std::string msg = file.string();
  if (sax.has_position()) msg += ":" + line_col(text, sax.position() == 0 ? 0 : sax.position() - 1);
  msg += ": ";
  if (!where.empty()) msg += where + ": ";
  msg += "invalid JSON: " + sax.problem();
  throw InputError(msg);
}

Json read_json_file(const std::filesystem::path& file) {
  return parse_json_text(read_input_file(file, kMaxJsonBytes), file);
}

std::string echo(const Json& v) {
  // Invalid UTF-8 inside a string would make dump() throw; replace it instead.
  std::string s = v.dump(-1, ' ', false, Json::error_handler_t::replace);
  if (s.size() <= kEchoChars) return s;
  const std::size_t n = s.size();
  s.resize(kEchoChars);
  // Do not cut a UTF-8 sequence in half.
  while (!s.empty() && (static_cast<unsigned char>(s.back()) & 0xC0) == 0x80) s.pop_back();
  if (!s.empty() && (static_cast<unsigned char>(s.back()) & 0x80)) s.pop_back();
  return s + "... (" + std::to_string(n) + " characters)";
}

std::string closest_key(std::string_view key, std::span<const std::string_view> allowed) {
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
  std::string where = key_path(key);
  // A key is input too: a 10 MB key must not become a 10 MB message.
  if (where.size() > 2 * kEchoChars) where = where.substr(0, 2 * kEchoChars) + "...";
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
  if (!value_.is_array() || index >= value_.size())
    fail("", "has no element " + std::to_string(index));
  return JsonReader(value_.at(index), file_, path_ + "[" + std::to_string(index) + "]");
}

void JsonReader::require_object() const {
  if (!value_.is_object()) fail("", "must be an object (got " + echo(value_) + ")");
}

std::size_t JsonReader::require_array() const {
  if (!value_.is_array()) fail("", "must be an array (got " + echo(value_) + ")");
  return value_.size();
}

void JsonReader::only_keys_in(std::span<const std::string_view> allowed) const {
  require_object();
  for (const auto& [k, v] : value_.items()) {
    if (std::find(allowed.begin(), allowed.end(), k) != allowed.end()) continue;
    const std::string near =
        closest_key(k, std::vector<std::string_view>(allowed.begin(), allowed.end()));
    fail(k, near.empty() ? "unknown key" : "unknown key (did you mean \"" + near + "\"?)");
  }
}

double JsonReader::number(std::string_view key) const {
  const Json& v = get(key);
  if (!v.is_number()) fail(key, "must be a number (got " + echo(v) + ")");
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail(key, "must be finite (got " + echo(v) + ")");
  return x;
}

double JsonReader::number_or(std::string_view key, double fallback) const {
  return has(key) ? number(key) : fallback;
}

double JsonReader::positive(std::string_view key) const {
  const double x = number(key);
  if (!(x > 0)) fail(key, "must be > 0 (got " + echo(get(key)) + ")");
  return x;
}

double JsonReader::in_range(std::string_view key, double lo, double hi, bool lo_open,
                            bool hi_open) const {
  const double x = number(key);
  const bool ok = (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
  if (!ok) {
    std::ostringstream r;
    r << "must lie in " << (lo_open ? "(" : "[") << lo << ", " << hi << (hi_open ? ")" : "]")
      << " (got " << echo(get(key)) << ")";
    fail(key, r.str());
  }
  return x;
}

long long JsonReader::integer(std::string_view key, long long lo, long long hi) const {
  const Json& v = get(key);
  if (!v.is_number_integer()) fail(key, "must be an integer (got " + echo(v) + ")");
  // An unsigned value above LLONG_MAX would wrap negative in get<long long>().
  if (v.is_number_unsigned() && v.get<std::uint64_t>() > static_cast<std::uint64_t>(hi)) {
    fail(key, "must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " +
                  echo(v) + ")");
  }
  const long long x = v.get<long long>();
  if (x < lo || x > hi) {
    fail(key, "must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " +
                  echo(v) + ")");
  }
  return x;
}

bool JsonReader::boolean_or(std::string_view key, bool fallback) const {
  if (!has(key)) return fallback;
  const Json& v = get(key);
  if (!v.is_boolean()) fail(key, "must be true or false (got " + echo(v) + ")");
  return v.get<bool>();
}

std::string JsonReader::string(std::string_view key) const {
  const Json& v = get(key);
  if (!v.is_string()) fail(key, "must be a string (got " + echo(v) + ")");
  return v.get<std::string>();
}

Vec3 JsonReader::vec3(std::string_view key) const {
  const Json& v = get(key);
  if (!v.is_array() || v.size() != 3 ||
      !std::all_of(v.begin(), v.end(), [](const Json& x) { return x.is_number(); })) {
    fail(key, "must be an array of 3 numbers (got " + echo(v) + ")");
  }
  Vec3 out(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
  if (!out.allFinite()) fail(key, "must be finite (got " + echo(v) + ")");
  return out;
}

Vec3 JsonReader::vec3_or(std::string_view key, const Vec3& fallback) const {
  return has(key) ? vec3(key) : fallback;
}

}  // namespace asperity::io
