// peer_cost_table RUNS.json COST.csv AGREEMENT.csv: the peer cost table (reports/peers/cost.md)
// from the repeats of `asperity crosscheck --cost-only` (each a DIR/cost.json, crosscheck.hpp),
// computed here, by the C++ that owns the median (solver/core/quantile.hpp), for
// tools/report/peer_cost.py, which runs the repeats and only formats what this writes.
//
// RUNS.json: {"codes": [code, ...], "scenes": [{"scene": NAME, "costs": [cost.json, ...],
// "errors": {code: why, ...}}, ...]}, the codes in the table's order (asperity first), a scene's
// cost.json files one per repeat that wrote one. Writes
// - COST.csv: per scene (that has a repeat) and code, the median over the repeats that ran it of
//   each of kKeys (empty where none reported it), its steps' CPU over asperity's, and the first
//   repeat's version and clock, with the code's error (a code that never ran: the error alone);
// - AGREEMENT.csv: per peer with its own CPU clock of the loop, the largest difference over the
//   scenes between that clock and its process CPU less a 0-step run: how far the 0-step
//   difference (the only measure LIGGGHTS has) can be trusted.
// Numbers in the shortest form that reads back to the same double (JSON's). Bad input: one line
// naming the file and the problem, exit 2.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "solver/core/quantile.hpp"
#include "solver/io/atomic_file.hpp"
#include "solver/io/csv.hpp"
#include "solver/io/json_file.hpp"

namespace {

using asperity::io::Json;

// The seconds of cost.json's entries, in the table's column order (crosscheck.cpp, cost_entry).
constexpr const char* kKeys[] = {"step_cpu_seconds",         "cpu_per_step_per_particle",
                                 "process_step_cpu_seconds", "loop_cpu_seconds",
                                 "loop_wall_seconds",        "run_cpu_seconds",
                                 "run_wall_seconds"};

// A cell as the table writes it: a string as it is, a number in JSON's shortest form, else empty.
std::string cell(const Json& v) {
  if (v.is_string()) return v.get<std::string>();
  return v.is_number() ? v.dump() : std::string();
}

// One code of one scene over the repeats.
struct Row {
  std::map<std::string, Json> value;  // column → cell
};

// Per peer (in the order a difference first shows), the largest difference of its two clocks.
using Agreement = std::vector<std::pair<std::string, double>>;

std::vector<Row> rows(const Json& runs, Agreement& agreement) {
  const std::vector<std::string> codes = runs.at("codes").get<std::vector<std::string>>();
  std::vector<Row> out;
  for (const Json& scene : runs.at("scenes")) {
    std::vector<Json> costs;
    for (const Json& file : scene.at("costs"))
      costs.push_back(asperity::io::read_json_file(file.get<std::string>()));
    if (costs.empty()) continue;
    const Json errors = scene.value("errors", Json::object());
    const std::size_t first = out.size();
    for (const std::string& code : codes) {
      std::vector<const Json*> got;
      for (const Json& c : costs)
        if (c.at("codes").contains(code)) got.push_back(&c.at("codes").at(code));
      Row r;
      r.value = {{"scene", scene.at("scene")},
                 {"particles", costs[0].at("particles")},
                 {"steps", costs[0].at("steps")},
                 {"dt", costs[0].at("dt")},
                 {"code", code},
                 {"repeats", got.size()},
                 {"error", errors.value(code, "")}};
      if (!got.empty()) {
        for (const char* key : kKeys) {
          std::vector<double> v;
          for (const Json* g : got)
            if (g->contains(key)) v.push_back(g->at(key).get<double>());
          r.value[key] = v.empty() ? Json() : Json(asperity::quantile(v, 0.5));
        }
        r.value["version"] = got[0]->at("version");
        r.value["step_cpu_from"] = got[0]->at("step_cpu_from");
      }
      out.push_back(r);
    }
    // × asperity, and the clocks' agreement, within the scene.
    const Json& base = out[first].value["step_cpu_seconds"];
    for (std::size_t i = first; i < out.size(); ++i) {
      std::map<std::string, Json>& v = out[i].value;
      if (!v.contains("step_cpu_seconds")) continue;
      if (base.is_number())
        v["over_asperity"] = v["step_cpu_seconds"].get<double>() / base.get<double>();
      const std::string code = v["code"].get<std::string>();
      if (code != "asperity" && v["process_step_cpu_seconds"].is_number() &&
          v["step_cpu_from"].get<std::string>().starts_with("the peer's")) {
        const double gap = std::abs(v["process_step_cpu_seconds"].get<double>() -
                                    v["step_cpu_seconds"].get<double>());
        auto it = std::find_if(agreement.begin(), agreement.end(),
                               [&](const auto& a) { return a.first == code; });
        if (it == agreement.end()) it = agreement.insert(agreement.end(), {code, 0.0});
        it->second = std::max(it->second, gap);
      }
    }
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  return asperity::io::table_program(
      argc, argv, 3, "peer_cost_table RUNS.json COST.csv AGREEMENT.csv", [&] {
        Agreement agreement;
        const std::vector<Row> table = rows(asperity::io::read_json_file(argv[1]), agreement);
        std::vector<std::string> header = {"scene", "particles", "steps", "dt", "code", "repeats"};
        header.insert(header.end(), std::begin(kKeys), std::end(kKeys));
        header.insert(header.end(), {"over_asperity", "step_cpu_from", "version", "error"});
        asperity::io::CsvWriter cost(header);
        for (const Row& r : table) {
          for (const std::string& h : header) {
            const auto it = r.value.find(h);
            cost.field(it == r.value.end() ? std::string() : cell(it->second));
          }
          cost.end_row();
        }
        asperity::io::write_atomically(argv[2], cost.str());
        asperity::io::CsvWriter agree({"code", "largest_difference_seconds"});
        for (const auto& [code, most] : agreement)
          agree.field(code).field(Json(most).dump()).end_row();
        asperity::io::write_atomically(argv[3], agree.str());
      });
}
