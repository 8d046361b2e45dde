// The one CSV writer (RFC 4180) of every table the suite writes: force.csv, energy.csv, the
// study's and the stability sweep's tables; and the reader of the plain tables a report's C++
// computes its statistics from (study/penalty_summary.cpp, benchmarks/collision_cost.cpp). A field
// holding a comma, a double quote, CR or LF is enclosed in double quotes with each quote doubled,
// so a failure message with a comma or a quote stays one field of its row.
#pragma once

#include <algorithm>
#include <fstream>
#include <initializer_list>
#include <optional>
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

// The fields of one line of plain fields (none quoted); a CR before the LF (Python's csv module
// ends its lines with CR LF) is dropped, and a trailing comma ends in an empty field.
inline std::vector<std::string> csv_split(std::string line) {
  if (!line.empty() && line.back() == '\r') line.pop_back();
  std::vector<std::string> out;
  std::stringstream s(line);
  for (std::string f; std::getline(s, f, ',');) out.push_back(f);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

// A table of plain fields read whole: its header and its rows (the line of row i is i + 2).
struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  // The index of column `name`; nullopt where the header has none.
  std::optional<std::size_t> column(std::string_view name) const {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) return std::nullopt;
    return static_cast<std::size_t>(it - header.begin());
  }
};

// nullopt where the file cannot be read or has no header line.
inline std::optional<CsvTable> read_csv_table(const std::string& file) {
  std::ifstream in(file);
  std::string line;
  if (!in || !std::getline(in, line)) return std::nullopt;
  CsvTable t{.header = csv_split(line)};
  while (std::getline(in, line)) t.rows.push_back(csv_split(line));
  return t;
}

}  // namespace asperity::io
