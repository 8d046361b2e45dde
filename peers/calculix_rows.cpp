// calculix_rows: the committed rows of reports/peers/calculix/ from the CalculiX gates' run folders
// (peers/calculix_rows.hpp computes each row; tests/peers/test_calculix.cpp's gates read their
// measures through the same functions).
//
//   calculix_rows levels LEVELS.csv LEVEL...               the sphere's CalculiX levels
//   calculix_rows particles PARTICLES.csv NAME LEVEL...    a particle's levels, both codes
//
// LEVEL: a level's folder (LEVEL/calculix/ and, for a particle, LEVEL/asperity/: the gates'
// scratch folders, or `asperity crosscheck --peer calculix --out LEVEL`; a particle's rows are
// those of the codes whose summary.json LEVEL holds). A row whose key (a/R, s
// and the step; particle, code and s) is already in the file replaces it, where it stands; a new
// row goes after the last of the same a/R or particle, else at the end. Each row written is
// printed with the fields it changed (old -> new), so rerunning a gate and this program shows
// whether the committed rows are reproduced. Exit 0, or 2 (bad input or usage).
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "peers/calculix_rows.hpp"
#include "solver/core/error.hpp"
#include "solver/io/atomic_file.hpp"
#include "solver/io/csv.hpp"

namespace {

namespace fs = std::filesystem;
namespace rows = asperity::peers::calculix_rows;
using Row = std::vector<std::string>;

constexpr const char* kUsage =
    "usage: calculix_rows levels LEVELS.csv LEVEL...\n"
    "       calculix_rows particles PARTICLES.csv NAME LEVEL...";

// Two values of `s` name the same level when they agree to the CSV's four decimals.
constexpr double kSameS = 5e-5;

struct Table {
  Row header;
  std::vector<Row> rows;
};

Table read_table(const fs::path& file, const Row& header) {
  if (!fs::exists(file)) return {.header = header};
  const asperity::io::CsvTable t = asperity::io::read_csv_table(file.string());
  if (t.header != header)
    throw asperity::InputError(file.string() + ": not the expected columns (" +
                               std::to_string(header.size()) + ", " + header[0] + " first)");
  Table out{.header = t.header};
  for (const Row& r : t.rows)
    if (!(r.empty() || (r.size() == 1 && r[0].empty()))) out.rows.push_back(r);
  return out;
}

// The fields of `now` that differ from `was`, "name old -> new".
std::string changes(const Row& header, const Row& was, const Row& now) {
  std::string out;
  for (std::size_t i = 0; i < header.size(); ++i) {
    const std::string old = i < was.size() ? was[i] : std::string();
    if (old == now[i]) continue;
    out += (out.empty() ? "" : "; ") + header[i] + " " + (old.empty() ? "(blank)" : old) + " -> " +
           (now[i].empty() ? "(blank)" : now[i]);
  }
  return out.empty() ? "reproduced" : out;
}

// Puts `row` into the table: in place of the row `same` matches, else after the last row with
// the same first field, else at the end; prints what it did.
template <class Same>
void put(Table& t, const Row& row, const Same& same) {
  std::string line;
  for (const std::string& f : row) line += (line.empty() ? "" : ",") + f;
  for (Row& r : t.rows) {
    if (!same(r)) continue;
    std::printf("%s\n  %s\n", line.c_str(), changes(t.header, r, row).c_str());
    r = row;
    return;
  }
  auto at = t.rows.end();
  for (auto it = t.rows.begin(); it != t.rows.end(); ++it)
    if ((*it)[0] == row[0]) at = it + 1;
  t.rows.insert(at, row);
  std::printf("%s\n  added\n", line.c_str());
}

void write_table(const fs::path& file, const Table& t) {
  std::string text;
  const auto line = [&text](const Row& r) {
    for (std::size_t i = 0; i < r.size(); ++i) text += (i ? "," : "") + r[i];
    text += "\n";
  };
  line(t.header);
  for (const Row& r : t.rows) line(r);
  asperity::io::write_atomically(file, text);
}

int levels(const fs::path& csv, const std::vector<fs::path>& dirs) {
  Table t = read_table(csv, rows::kSphereHeader);
  for (const fs::path& d : dirs) {
    const Row row = rows::sphere_fields(rows::sphere_level(d / "calculix"));
    put(t, row, [&](const Row& r) {
      for (std::size_t i = 0; i < rows::kSphereKey; ++i)
        if (i >= r.size() || r[i] != row[i]) return false;
      return true;
    });
  }
  write_table(csv, t);
  return asperity::kExitOk;
}

int particles(const fs::path& csv, const std::string& name, const std::vector<fs::path>& dirs) {
  Table t = read_table(csv, rows::kParticleHeader);
  for (const fs::path& d : dirs) {
    for (const char* code : {"asperity", "calculix"}) {
      if (!fs::exists(d / code / "summary.json")) continue;
      const rows::ParticleLevel l = rows::particle_level(d, code);
      put(t, rows::particle_fields(name, l), [&](const Row& r) {
        return r.size() > 2 && r[0] == name && r[1] == code &&
               std::abs(std::stod(r[2]) - l.s) < kSameS;
      });
    }
  }
  write_table(csv, t);
  return asperity::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> a(argv + 1, argv + argc);
  try {
    if (a.size() >= 3 && a[0] == "levels")
      return levels(a[1], std::vector<fs::path>(a.begin() + 2, a.end()));
    if (a.size() >= 4 && a[0] == "particles")
      return particles(a[1], a[2], std::vector<fs::path>(a.begin() + 3, a.end()));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "calculix_rows: %s\n", e.what());
    return asperity::kExitBadInput;
  }
  std::fprintf(stderr, "%s\n", kUsage);
  return asperity::kExitBadInput;
}
