// Our own ASCII OFF reader. CGAL's (CGAL/IO/OFF.h) trusts its input: it reserves what the header
// declares and resizes a face's index list to the count the face line starts with, so a face
// declaring 4e13 vertices was an allocation-size-too-big under ASan (fuzz_mesh_off, CI of round
// 2) however the header had been pre-checked. Here nothing is allocated for a count before the
// bytes that must hold it are known to exist. Format: Geomview's OFF description
// (http://www.geomview.org/docs/html/OFF.html), the ASCII form.
#include "solver/geometry/read_off.hpp"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "solver/core/error.hpp"
#include "solver/geometry/mesh_text.hpp"

namespace asperity::geometry {
namespace {

using text::shown;

// Counts above this are refused as absurd (a 1 GiB file holds at most 2^29 ASCII numbers), which
// also keeps every product of counts and byte sizes below 2^63.
constexpr std::int64_t kMaxCount = std::int64_t{1} << 40;

class OffReader {
 public:
  OffReader(const std::string& file, std::string_view bytes)
      : file_(file), bytes_(bytes), lines_(bytes) {}

  PolygonSoup read() {
    header();
    vertices();
    faces();
    return std::move(soup_);
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(file_ + ": " + problem);
  }
  [[noreturn]] void fail_line(const std::string& what, const std::string& problem) const {
    fail("OFF line " + std::to_string(lines_.number()) + " (" + what + "): " + problem);
  }

  // The next line with content, '#' comments removed; false at the end of the file.
  bool next_content(std::string_view& line) {
    while (lines_.next(line)) {
      line = line.substr(0, line.find('#'));
      for (char c : line)
        if (!text::is_space(c)) return true;
    }
    return false;
  }

  // [ST][C][N][4]OFF, then the counts on the same line or the next with content.
  void header() {
    std::string_view line, keyword;
    text::Tokens tokens({});
    if (!next_content(line) || !(tokens = text::Tokens(line)).next(keyword)) {
      fail("not a valid OFF file: no content" + text::wrong_extension_hint(bytes_, "OFF"));
    }
    std::string_view k = keyword;
    const auto take = [&k](std::string_view prefix) {
      const bool has = k.substr(0, prefix.size()) == prefix;
      if (has) k.remove_prefix(prefix.size());
      return has;
    };
    take("ST");
    take("C");
    take("N");
    homogeneous_ = take("4");
    if (k == "nOFF") fail_line("header", "nOFF (a dimension other than 3) is not supported");
    if (k != "OFF") {
      fail("not a valid OFF file: line " + std::to_string(lines_.number()) +
           " should start with the keyword OFF (or COFF, NOFF, STOFF, 4OFF), not " +
           shown(keyword) + text::wrong_extension_hint(bytes_, "OFF"));
    }
    std::string_view first;
    if (!tokens.next(first)) {
      if (!next_content(line)) fail_line("header", "the file ends before the counts");
      tokens = text::Tokens(line);
      tokens.next(first);
    }
    if (first == "BINARY") {
      fail_line("header", "binary OFF is not supported (write the mesh as ASCII OFF)");
    }
    std::string_view second;
    tokens.next(second);
    const auto nv = text::to_integer(first), nf = text::to_integer(second);
    if (!nv || !nf || *nv < 0 || *nf < 0 || *nv >= kMaxCount || *nf >= kMaxCount) {
      fail("OFF header: vertex and face counts must be whole numbers below 2^40 (got " +
           shown(first) + ", " + shown(second) + ", line " + std::to_string(lines_.number()) + ")");
    }
    nv_ = *nv;
    nf_ = *nf;
    // Every ASCII number takes at least two bytes (a digit and a separator): a vertex at least
    // 2 per coordinate, a face at least 8 ("3 0 1 2\n").
    const std::int64_t coords = homogeneous_ ? 4 : 3;
    const auto left = static_cast<std::int64_t>(lines_.rest().size());
    const std::int64_t need = nv_ * 2 * coords + nf_ * 8;
    if (need > left) {
      fail("OFF header declares " + std::to_string(nv_) + " vertices and " + std::to_string(nf_) +
           " faces, which need at least " + std::to_string(need) + " bytes; " +
           std::to_string(left) + " follow the header (line " + std::to_string(lines_.number()) +
           ")");
    }
  }

  void vertices() {
    soup_.points.resize(3, static_cast<Eigen::Index>(nv_));
    std::size_t nonfinite = 0, first_bad_line = 0;
    for (std::int64_t v = 0; v < nv_; ++v) {
      std::string_view line;
      if (!next_content(line)) {
        fail("OFF: the file ends after " + std::to_string(v) + " of " + std::to_string(nv_) +
             " vertices");
      }
      const std::string what = "vertex " + std::to_string(v);
      text::Tokens tokens(line);
      double x[4] = {0, 0, 0, 1};
      const int n = homogeneous_ ? 4 : 3;
      for (int c = 0; c < n; ++c) {
        std::string_view t;
        if (!tokens.next(t)) {
          fail_line(what, std::to_string(c) + " coordinates, expected " + std::to_string(n));
        }
        const auto value = text::to_double(t);
        if (!value) fail_line(what, shown(t) + " is not a number");
        x[c] = *value;
      }
      for (int c = 0; c < 3; ++c) {
        const double p = homogeneous_ ? x[c] / x[3] : x[c];
        if (!std::isfinite(p)) {
          ++nonfinite;
          if (first_bad_line == 0) first_bad_line = lines_.number();
        }
        soup_.points(c, static_cast<Eigen::Index>(v)) = p;
      }
    }
    if (nonfinite > 0) {
      fail(std::to_string(nonfinite) +
           " NaN or infinite coordinate values (OFF, the first on line " +
           std::to_string(first_bad_line) + ")");
    }
  }

  void faces() {
    soup_.polygons.reserve(static_cast<std::size_t>(nf_));
    for (std::int64_t f = 0; f < nf_; ++f) {
      std::string_view line;
      if (!next_content(line)) {
        fail("OFF: the file ends after " + std::to_string(f) + " of " + std::to_string(nf_) +
             " faces");
      }
      const std::string what = "face " + std::to_string(f);
      text::Tokens tokens(line);
      std::string_view t;
      tokens.next(t);
      const auto n = text::to_integer(t);
      if (!n) fail_line(what, "vertex count " + shown(t) + " is not a whole number");
      if (*n < 3) {
        fail_line(what, std::to_string(*n) + " vertices; a face needs at least 3");
      }
      // The indices are on this line: its token count bounds the allocation.
      const std::size_t held = tokens.count();
      if (static_cast<std::uint64_t>(*n) > held) {
        fail_line(what, "declares " + std::to_string(*n) + " vertices but the line holds " +
                            std::to_string(held) + " numbers after the count");
      }
      std::vector<int> polygon;
      polygon.reserve(static_cast<std::size_t>(*n));
      for (std::int64_t i = 0; i < *n; ++i) {
        tokens.next(t);
        const auto index = text::to_integer(t);
        if (!index) fail_line(what, "vertex index " + shown(t) + " is not a whole number");
        if (*index < 0 || *index >= nv_) {
          fail_line(what, "vertex index " + std::to_string(*index) +
                              " out of range (the file has " + std::to_string(nv_) + " vertices)");
        }
        polygon.push_back(static_cast<int>(*index));
      }
      soup_.polygons.push_back(std::move(polygon));
    }
  }

  const std::string& file_;
  std::string_view bytes_;
  text::Lines lines_;
  bool homogeneous_ = false;
  std::int64_t nv_ = 0, nf_ = 0;
  PolygonSoup soup_;
};

}  // namespace

PolygonSoup read_off(const std::string& file, std::string_view bytes) {
  return OffReader(file, bytes).read();
}

}  // namespace asperity::geometry
