// The one CSV writer (RFC 4180) of every table the suite writes: force.csv, energy.csv, the
// study's and the stability sweep's tables; and the reader of the plain tables a report's C++
// computes its statistics from (study/penalty_summary.cpp, benchmarks/collision_cost.cpp). A field
// holding a comma, a double quote, CR or LF is enclosed in double quotes with each quote doubled,
// so a failure message with a comma or a quote stays one field of its row.
#pragma once

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <exception>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "solver/core/error.hpp"

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

// A table of plain fields read whole: its header and its rows (the line of row k is k + 2). The
// reading throws InputError with the problem alone (the caller names the file).
struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  // The index of column `name`; nullopt where the header has none.
  std::optional<std::size_t> column(std::string_view name) const {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) return std::nullopt;
    return static_cast<std::size_t>(it - header.begin());
  }
  // The same, required.
  std::size_t required(std::string_view name) const {
    const std::optional<std::size_t> i = column(name);
    if (!i) throw InputError("has no column \"" + std::string(name) + "\"");
    return *i;
  }
  // The number in row k, column i: the whole field ("nan" and "inf" read as such, a leading '+'
  // allowed).
  double number(std::size_t k, std::size_t i) const {
    std::string_view t = i < rows[k].size() ? std::string_view(rows[k][i]) : std::string_view();
    if (t.size() > 1 && t[0] == '+' && t[1] != '-') t.remove_prefix(1);
    double x = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), x);
    if (t.empty() || ec != std::errc() || end != t.data() + t.size()) {
      throw InputError("line " + std::to_string(k + 2) + ", column \"" + header[i] +
                       "\": not a number");
    }
    return x;
  }
};

inline CsvTable read_csv_table(const std::string& file) {
  std::ifstream in(file);
  std::string line;
  if (!in || !std::getline(in, line)) throw InputError("cannot be read, or is empty");
  CsvTable t{.header = csv_split(line)};
  while (std::getline(in, line)) t.rows.push_back(csv_split(line));
  return t;
}

// The main of a program that computes a report's table from another program's files
// (benchmarks/collision_cost, study/penalty_summary, peers/peer_cost_table): `body` when argv
// holds `args` arguments, else the usage; input it cannot use (any exception) is one line naming
// the first argument and the problem. Exit 0, or 2 (bad input or usage; docs/contract.md).
template <class Body>
int table_program(int argc, char** argv, int args, const char* usage, Body body) {
  if (argc != args + 1) {
    std::fprintf(stderr, "usage: %s\n", usage);
    return kExitBadInput;
  }
  try {
    body();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", argv[1], e.what());
    return kExitBadInput;
  }
  return kExitOk;
}

}  // namespace asperity::io
