// docs/scenes.md documents every key the scene loader accepts (its key table,
// scene/scene_keys.hpp), and nothing it does not: a key added to the loader without a row in the
// doc, or a row left behind by a removed key, fails here.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "scene/scene_keys.hpp"

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

}  // namespace
}  // namespace asperity::scene
