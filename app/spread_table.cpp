// spread_table SAMPLES.csv SPREAD.csv: the median and spread of repeated measurements by group,
// for the report writers that repeat a measurement and only format the result
// (tools/report/perf_table.py, peer_table.py, tools/measure_scaling.py),
// computed here by the one quantile (solver/core/quantile.hpp, asperity::spread).
//
// SAMPLES.csv: key columns (any number, plain fields), then `value`, the last column: one row per
// sample, a finite number (a NaN has no place in an order, so no median). Writes SPREAD.csv: per
// group of equal keys, in the order the groups first show, the key columns, `count`, `median`,
// `min` and `max`, numbers in the shortest form that reads back to the same double (JSON's). Bad
// input: one line naming the file and the problem, exit 2.
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "solver/core/error.hpp"
#include "solver/core/quantile.hpp"
#include "solver/io/atomic_file.hpp"
#include "solver/io/csv.hpp"
#include "solver/io/json_file.hpp"

namespace {

// A number as the table writes it: JSON's shortest round trip.
std::string shortest(double x) {
  return asperity::io::Json(x).dump();
}

}  // namespace

int main(int argc, char** argv) {
  return asperity::io::table_program(argc, argv, 2, "spread_table SAMPLES.csv SPREAD.csv", [&] {
    const asperity::io::CsvTable t = asperity::io::read_csv_table(argv[1]);
    if (t.header.empty() || t.header.back() != "value")
      throw asperity::InputError("the last column must be \"value\"");
    const std::size_t keys = t.header.size() - 1;
    std::vector<std::vector<std::string>> order;  // the groups as they first show
    std::map<std::vector<std::string>, std::vector<double>> samples;
    for (std::size_t k = 0; k < t.rows.size(); ++k) {
      if (t.rows[k].size() != t.header.size()) {
        throw asperity::InputError("line " + std::to_string(k + 2) + ": " +
                                   std::to_string(t.rows[k].size()) + " fields, the header has " +
                                   std::to_string(t.header.size()));
      }
      const std::vector<std::string> key(t.rows[k].begin(), t.rows[k].begin() + keys);
      auto [it, fresh] = samples.try_emplace(key);
      if (fresh) order.push_back(key);
      const double x = t.number(k, keys);
      if (!std::isfinite(x))
        throw asperity::InputError("line " + std::to_string(k + 2) + ": value is not finite");
      it->second.push_back(x);
    }
    std::vector<std::string> header(t.header.begin(), t.header.begin() + keys);
    header.insert(header.end(), {"count", "median", "min", "max"});
    asperity::io::CsvWriter out(header);
    for (const std::vector<std::string>& key : order) {
      for (const std::string& k : key) out.field(k);
      const asperity::Spread s = asperity::spread(samples.at(key));
      out.field(std::to_string(s.count))
          .field(shortest(s.median))
          .field(shortest(s.min))
          .field(shortest(s.max))
          .end_row();
    }
    asperity::io::write_atomically(argv[2], out.str());
  });
}
