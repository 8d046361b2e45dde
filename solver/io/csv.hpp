// The one CSV writer (RFC 4180) of every table the suite writes: force.csv, energy.csv, the
// study's and the stability sweep's tables. A field holding a comma, a double quote, CR or LF
// is enclosed in double quotes with each quote doubled, so a failure message with a comma or a
// quote stays one field of its row.
#pragma once

#include <initializer_list>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace asperity::io {

inline std::string csv_field(std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

// Rows of numbers (at `precision` significant digits) and text fields, comma-separated.
class CsvWriter {
 public:
  explicit CsvWriter(std::initializer_list<std::string_view> header, int precision = 10) {
    s_.precision(precision);
    for (std::string_view h : header) field(h);
    end_row();
  }
  explicit CsvWriter(const std::vector<std::string>& header, int precision = 10) {
    s_.precision(precision);
    for (const std::string& h : header) field(h);
    end_row();
  }
  CsvWriter& field(std::string_view text) {
    separate();
    s_ << csv_field(text);
    return *this;
  }
  CsvWriter& number(double x) {
    separate();
    s_ << x;
    return *this;
  }
  CsvWriter& end_row() {
    s_ << '\n';
    first_ = true;
    return *this;
  }
  std::string str() const { return s_.str(); }

 private:
  void separate() {
    if (!first_) s_ << ',';
    first_ = false;
  }
  std::ostringstream s_;
  bool first_ = true;
};

}  // namespace asperity::io
