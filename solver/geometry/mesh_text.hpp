// Scanning the text of a mesh file (OFF, ASCII PLY) without trusting it: lines and tokens are
// views into the file's bytes, numbers are parsed with std::from_chars (no locale, no
// allocation, a token must be one number entirely), and line numbers are kept for the messages.
#pragma once

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>

namespace asperity::geometry::text {

inline bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

// The file's lines one at a time, without their "\n" or "\r\n".
class Lines {
 public:
  explicit Lines(std::string_view bytes) : rest_(bytes) {}
  bool next(std::string_view& line) {
    if (rest_.empty()) return false;
    const std::size_t end = rest_.find('\n');
    line = rest_.substr(0, end);
    rest_ = end == std::string_view::npos ? std::string_view() : rest_.substr(end + 1);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    ++number_;
    return true;
  }
  std::size_t number() const { return number_; }   // 1-based, of the line last returned
  std::string_view rest() const { return rest_; }  // the bytes after that line

 private:
  std::string_view rest_;
  std::size_t number_ = 0;
};

// Whitespace-separated tokens of a piece of text, counting the newlines passed (so a token's
// line is known in a token stream that spans lines: ASCII PLY).
class Tokens {
 public:
  explicit Tokens(std::string_view text, std::size_t first_line = 1)
      : rest_(text), line_(first_line) {}
  bool next(std::string_view& token) {
    skip_space();
    if (rest_.empty()) return false;
    std::size_t n = 0;
    while (n < rest_.size() && !is_space(rest_[n])) ++n;
    token = rest_.substr(0, n);
    rest_.remove_prefix(n);
    return true;
  }
  // How many tokens are left (a walk over the rest: call it on one line, not on a whole file).
  std::size_t count() const {
    Tokens copy = *this;
    std::string_view t;
    std::size_t n = 0;
    while (copy.next(t)) ++n;
    return n;
  }
  std::size_t line() const { return line_; }  // of the token last returned (or the next)
  std::size_t bytes_left() const { return rest_.size(); }

 private:
  void skip_space() {
    while (!rest_.empty() && is_space(rest_.front())) {
      if (rest_.front() == '\n') ++line_;
      rest_.remove_prefix(1);
    }
  }
  std::string_view rest_;
  std::size_t line_;
};

// A number token: decimal or exponent form, a leading '+' allowed, "nan" and "inf" accepted (the
// caller counts them as non-finite values and says so).
inline std::optional<double> to_double(std::string_view t) {
  if (t.size() > 1 && t[0] == '+' && t[1] != '-') t.remove_prefix(1);
  double x = 0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), x);
  if (ec != std::errc() || end != t.data() + t.size()) return std::nullopt;
  return x;
}

// A whole-number token that fits in int64 (a leading '+' allowed).
inline std::optional<std::int64_t> to_integer(std::string_view t) {
  if (t.size() > 1 && t[0] == '+' && t[1] != '-') t.remove_prefix(1);
  std::int64_t x = 0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), x);
  if (ec != std::errc() || end != t.data() + t.size()) return std::nullopt;
  return x;
}

// A token for a message: quoted, at most 20 characters, anything unprintable as '?' (the
// message stays one printable line whatever the file holds).
inline std::string shown(std::string_view t) {
  std::string s = "\"";
  for (std::size_t i = 0; i < t.size() && i < 20; ++i) {
    const unsigned char c = static_cast<unsigned char>(t[i]);
    s += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
  }
  if (t.size() > 20) s += "...";
  return s + "\"";
}

inline std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// What a file's first bytes look like ("PLY", "ASCII STL", "OFF", "OBJ" or ""), to turn "does
// not parse" into "wrong extension?".
inline std::string sniff_format(std::string_view head) {
  std::size_t i = 0;
  while (i < head.size() && is_space(head[i])) ++i;
  const std::string h = lower(std::string(head.substr(i, 8)));
  if (h.rfind("ply", 0) == 0) return "PLY";
  if (h.rfind("solid", 0) == 0) return "ASCII STL";
  if (h.rfind("off", 0) == 0 || h.rfind("coff", 0) == 0 || h.rfind("noff", 0) == 0) return "OFF";
  if (h.rfind("v ", 0) == 0 || h.rfind("# ", 0) == 0 || h.rfind("o ", 0) == 0 ||
      h.rfind("mtllib", 0) == 0)
    return "OBJ";
  return "";
}

// " (the content looks like X; wrong extension?)" when the bytes look like another format than
// FORMAT, else "".
inline std::string wrong_extension_hint(std::string_view bytes, const std::string& format) {
  const std::string looks = sniff_format(bytes.substr(0, 64));
  if (looks.empty() || looks.find(format) != std::string::npos) return "";
  return " (the content looks like " + looks + "; wrong extension?)";
}

}  // namespace asperity::geometry::text
