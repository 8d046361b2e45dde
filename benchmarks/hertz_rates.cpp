// hertz_rates: the Richardson columns of reports/fem/hertz_convergence.md and the lines of its
// limits against a/R, computed by the C++ that owns the rules (solver/core/richardson.hpp,
// least_squares.hpp) for tools/report/hertz_convergence_table.py, which groups bench_hertz's
// levels into sequences and only reads what this writes.
//
// Reads from standard input one sequence per line, "coarse middle fine ratio" (the three levels'
// errors against Hertz, coarse first, and the refinement ratio between them); writes one line per
// input line, "order finest_error limit" (RichardsonRate).
// With --line, each input line is the points "x1 y1 x2 y2 ..." (two or more) and each output line
// the least-squares line through them, "intercept slope intercept_error slope_error" (LineFit;
// the errors NaN for two points).
// To the last bit (%.17g), so the table formats exactly the doubles computed here. Bad input: one
// line naming the line, exit 2.
#include <cstdio>
#include <cstring>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "solver/core/least_squares.hpp"
#include "solver/core/richardson.hpp"
#include "solver/geometry/mesh_text.hpp"

namespace {

// The numbers of a line, each a whole word ("nan" and "inf" read as such: a level without a
// value stays NaN); nullopt where a word is not a number.
std::optional<std::vector<double>> numbers(const std::string& line) {
  std::istringstream in(line);
  std::vector<double> v;
  for (std::string word; in >> word;) {
    const std::optional<double> x = asperity::geometry::text::to_double(word);
    if (!x) return std::nullopt;
    v.push_back(*x);
  }
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  const bool line_fit = argc == 2 && std::strcmp(argv[1], "--line") == 0;
  if (argc != 1 && !line_fit) {
    std::fprintf(stderr,
                 "usage: hertz_rates < SEQUENCES (lines: coarse middle fine ratio)\n"
                 "       hertz_rates --line < POINTS (lines: x1 y1 x2 y2 ...)\n");
    return 2;
  }
  std::string line;
  for (long n = 1; std::getline(std::cin, line); ++n) {
    const std::optional<std::vector<double>> v = numbers(line);
    if (line_fit && v && v->size() >= 4 && v->size() % 2 == 0) {
      std::vector<double> x, y;
      for (std::size_t i = 0; i < v->size(); i += 2) x.push_back((*v)[i]), y.push_back((*v)[i + 1]);
      const asperity::LineFit f = asperity::fit_line(x, y);
      std::printf("%.17g %.17g %.17g %.17g\n", f.intercept, f.slope, f.intercept_error,
                  f.slope_error);
    } else if (!line_fit && v && v->size() == 4) {
      const asperity::RichardsonRate r =
          asperity::richardson_rate((*v)[0], (*v)[1], (*v)[2], (*v)[3]);
      std::printf("%.17g %.17g %.17g\n", r.order, r.finest_error, r.limit);
    } else {
      std::fprintf(stderr, "hertz_rates: stdin line %ld: expected %s, got \"%s\"\n", n,
                   line_fit ? "pairs of numbers \"x1 y1 x2 y2 ...\""
                            : "four numbers \"coarse middle fine ratio\"",
                   line.c_str());
      return 2;
    }
  }
  return 0;
}
