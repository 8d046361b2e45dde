// docs/scenes.md documents every key the scene loader accepts (its key table,
// scene/scene_keys.hpp), and nothing it does not: a key added to the loader without a row in the
// doc, or a row left behind by a removed key, fails here. The same for the keys of summary.json
// (run/summary_keys.hpp, the table validation cases are checked against).
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "solver/run/summary_keys.hpp"
#include "solver/scene/scene_keys.hpp"

namespace asperity::scene {
namespace {

// The first-column keys of the tables in the "## Scene keys" section: rows "| `key` | ...".
std::set<std::string> documented_keys() {
  std::ifstream in(std::string(ASPERITY_SOURCE_DIR) + "/docs/scenes.md");
  EXPECT_TRUE(in) << "docs/scenes.md is missing";
  std::set<std::string> out;
  bool in_section = false;
  const std::regex row(R"(^\| `([^`]+)` \|)");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("## ", 0) == 0) in_section = line == "## Scene keys";
    std::smatch m;
    if (in_section && std::regex_search(line, m, row)) out.insert(m[1]);
  }
  return out;
}

TEST(SceneKeys, EveryAcceptedKeyIsDocumented) {
  const std::set<std::string> doc = documented_keys();
  int checked = 0;
  for (const keys::Table& t : keys::kTables) {
    for (const std::string_view k : t.keys) {
      const std::string path = std::string(t.prefix) + std::string(k);
      EXPECT_TRUE(doc.count(path)) << "docs/scenes.md has no row for `" << path << "`";
      ++checked;
    }
  }
  EXPECT_GT(checked, 40);  // the tables are really there
}

TEST(SceneKeys, EveryDocumentedKeyIsAccepted) {
  std::set<std::string> accepted;
  for (const keys::Table& t : keys::kTables) {
    for (const std::string_view k : t.keys) accepted.insert(std::string(t.prefix) + std::string(k));
  }
  for (const std::string& k : documented_keys()) {
    EXPECT_TRUE(accepted.count(k))
        << "docs/scenes.md documents `" << k << "`, which the loader does not accept";
  }
}

// The keys in the first column of the table under the heading `heading` ("### ..."): every
// backticked name in "| `a`, `b` | ..." rows.
std::set<std::string> first_column_keys(const std::string& heading) {
  std::ifstream in(std::string(ASPERITY_SOURCE_DIR) + "/docs/scenes.md");
  EXPECT_TRUE(in) << "docs/scenes.md is missing";
  std::set<std::string> out;
  bool in_section = false;
  const std::regex key("`([a-z_]+)`");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("#", 0) == 0) in_section = line == heading;
    if (!in_section || line.rfind("| ", 0) != 0) continue;
    const std::string cell = line.substr(2, line.find(" |", 1) - 2);
    for (std::sregex_iterator m(cell.begin(), cell.end(), key), end; m != end; ++m) {
      out.insert((*m)[1]);
    }
  }
  return out;
}

void expect_same_keys(const std::string& heading, const std::set<std::string>& table) {
  const std::set<std::string> doc = first_column_keys(heading);
  EXPECT_GT(doc.size(), 10u) << "no key table under " << heading;
  for (const std::string& k : table) {
    EXPECT_TRUE(doc.count(k)) << "docs/scenes.md " << heading << " has no row for `" << k << "`";
  }
  for (const std::string& k : doc) {
    EXPECT_TRUE(table.count(k)) << "docs/scenes.md " << heading << " documents `" << k
                                << "`, which run/summary_keys.hpp does not list";
  }
}

TEST(SummaryKeys, TheRunTableAndTheDocAgree) {
  std::set<std::string> table;
  for (const std::string_view k : run::summary_keys::kRun) table.emplace(k);
  for (const std::string_view k : run::summary_keys::kRunStructured) table.emplace(k);
  expect_same_keys("### `summary.json`", table);
}

TEST(SummaryKeys, TheSweepTableAndTheDocAgree) {
  std::set<std::string> table;
  for (const std::string_view k : run::summary_keys::kSweep) table.emplace(k);
  expect_same_keys("### `summary.json` of a stability sweep (`asperity stability`)", table);
}

}  // namespace
}  // namespace asperity::scene
