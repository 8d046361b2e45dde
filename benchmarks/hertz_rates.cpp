// hertz_rates: the Richardson columns of reports/fem/hertz_convergence.md, computed by the C++
// that owns the rule (solver/core/richardson.hpp) for tools/report/hertz_convergence_table.py,
// which groups bench_hertz's levels into sequences and only reads what this writes.
//
// Reads from standard input one sequence per line, "coarse middle fine ratio" (the three levels'
// errors against Hertz, coarse first, and the refinement ratio between them); writes one line per
// input line, "order finest_error limit" (RichardsonRate), to the last bit (%.17g), so the table
// formats exactly the doubles computed here. Bad input: one line naming the line, exit 2.
#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>

#include "solver/core/richardson.hpp"
#include "solver/geometry/mesh_text.hpp"

int main(int argc, char**) {
  if (argc != 1) {
    std::fprintf(stderr, "usage: hertz_rates < SEQUENCES (lines: coarse middle fine ratio)\n");
    return 2;
  }
  std::string line;
  for (long n = 1; std::getline(std::cin, line); ++n) {
    // Four numbers, each a whole word ("nan" and "inf" read as such: a level without a value
    // stays NaN).
    std::istringstream in(line);
    double v[4] = {};
    bool ok = true;
    for (int i = 0; i < 4 && ok; ++i) {
      std::string word;
      const std::optional<double> x =
          in >> word ? asperity::geometry::text::to_double(word) : std::nullopt;
      ok = x.has_value();
      if (ok) v[i] = *x;
    }
    std::string rest;
    if (!ok || (in >> rest)) {
      std::fprintf(stderr,
                   "hertz_rates: stdin line %ld: expected four numbers "
                   "\"coarse middle fine ratio\", got \"%s\"\n",
                   n, line.c_str());
      return 2;
    }
    const asperity::RichardsonRate r = asperity::richardson_rate(v[0], v[1], v[2], v[3]);
    std::printf("%.17g %.17g %.17g\n", r.order, r.finest_error, r.limit);
  }
  return 0;
}
