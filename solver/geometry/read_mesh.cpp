// Reading surface meshes: OFF and PLY with our own bounded readers (read_off.cpp, read_ply.cpp),
// STL and OBJ with CGAL's stream I/O; the checks before and after turn every kind of bad file into
// one line naming the file and the defect (issue 3, "Reading"; docs/hostile.md).
#include "solver/geometry/read_mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/STL.h>

#include "solver/core/error.hpp"
#include "solver/geometry/mesh_text.hpp"
#include "solver/geometry/read_off.hpp"
#include "solver/geometry/read_ply.hpp"

namespace asperity::geometry {
namespace {
namespace fs = std::filesystem;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using text::lower;
using text::sniff_format;

[[noreturn]] void fail(const fs::path& file, const std::string& problem) {
  throw InputError(file.string() + ": " + problem);
}

std::string read_head(const fs::path& file, std::size_t n) {
  std::ifstream in(file, std::ios::binary);
  std::string head(n, '\0');
  in.read(head.data(), static_cast<std::streamsize>(n));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return head;
}

// Binary STL vertices (not normals, which readers ignore) must be finite: a NaN breaks the
// reader's point merging and surfaces later as a misleading "open mesh".
void check_binary_stl_finite(const fs::path& file, std::uint32_t count) {
  std::ifstream in(file, std::ios::binary);
  in.seekg(84);
  std::array<char, 50> rec{};
  std::size_t bad = 0;
  for (std::uint32_t t = 0; t < count && in.read(rec.data(), rec.size()); ++t) {
    for (int v = 1; v < 4; ++v) {  // floats 0-2 are the normal, then three vertices
      std::array<float, 3> x{};
      std::memcpy(x.data(), rec.data() + 12 * v, 12);
      if (!std::all_of(x.begin(), x.end(), [](float c) { return std::isfinite(c); })) ++bad;
    }
  }
  if (bad > 0) {
    fail(file, std::to_string(bad) + " vertices with NaN or infinite coordinates (binary STL, " +
                   "counted per triangle)");
  }
}

// Binary STL: 80-byte header, uint32 triangle count, 50 bytes per triangle. A file that does not
// start with "solid", or whose size matches that layout, is binary; its size must hold every
// declared triangle (CGAL would otherwise fail without saying why).
void check_binary_stl_size(const fs::path& file, std::uintmax_t size) {
  const std::string head = read_head(file, 84);
  const bool says_solid = lower(head.substr(0, 5)) == "solid";
  if (size < 84) {
    if (says_solid) return;  // a short ASCII file; the parser decides
    fail(file, "truncated binary STL: " + std::to_string(size) +
                   " bytes, shorter than the 84-byte header");
  }
  std::uint32_t count = 0;
  std::memcpy(&count, head.data() + 80, 4);  // little-endian on every platform we build for
  const std::uintmax_t expected = 84 + 50 * static_cast<std::uintmax_t>(count);
  if (size == expected) {
    check_binary_stl_finite(file, count);
    return;
  }
  if (says_solid) return;  // ASCII
  if (size < expected) {
    fail(file, "truncated binary STL: header declares " + std::to_string(count) + " triangles (" +
                   std::to_string(expected) + " bytes) but the file has " + std::to_string(size) +
                   " bytes (" + std::to_string((size - 84) / 50) + " whole triangles)");
  }
}

// Literal nan/inf tokens in a text file: the stream parsers stop at them, so say so.
std::size_t count_nonfinite_tokens(const fs::path& file) {
  std::ifstream in(file);
  std::string token;
  std::size_t n = 0;
  while (in >> token) {
    const std::string t = lower(token);
    const std::size_t s = (!t.empty() && (t[0] == '-' || t[0] == '+')) ? 1 : 0;
    if (t.compare(s, 3, "nan") == 0 || t.compare(s, 3, "inf") == 0) ++n;
  }
  return n;
}

// CGAL's readers may print their own diagnostics to std::cerr (its PLY reader, used before
// read_ply.cpp, printed "incorrect file format"); the contract allows one line on stderr, ours,
// so they are held while reading.
// std::cerr is one object for the whole process: two threads swapping its buffer at once would
// restore each other's (then destroyed) sink, so the swap is held under one lock.
class QuietCerr {
 public:
  QuietCerr() : lock_(mutex()), saved_(std::cerr.rdbuf(sink_.rdbuf())) {}
  ~QuietCerr() { std::cerr.rdbuf(saved_); }
  QuietCerr(const QuietCerr&) = delete;
  QuietCerr& operator=(const QuietCerr&) = delete;

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  std::lock_guard<std::mutex> lock_;
  std::ostringstream sink_;
  std::streambuf* saved_;
};

// STL and OBJ through CGAL's readers (fuzzed clean: fuzz_mesh_stl, fuzz_mesh_obj), with the binary
// STL size checked first.
PolygonSoup read_with_cgal(const fs::path& file, const std::string& format, std::uintmax_t size) {
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  const std::string name = file.string();
  bool ok = false;
  {
    QuietCerr quiet;
    if (format == "STL") {
      check_binary_stl_size(file, size);
      ok = CGAL::IO::read_STL(name, points, polygons);
    } else {
      ok = CGAL::IO::read_OBJ(name, points, polygons);
    }
  }
  if (!ok) {
    if (const std::size_t bad = count_nonfinite_tokens(file); bad > 0 && format != "STL") {
      fail(file, std::to_string(bad) + " NaN or infinite coordinate values");
    }
    const std::string looks = sniff_format(read_head(file, 64));
    std::string hint;
    if (!looks.empty() && looks.find(format) == std::string::npos) {
      hint = " (the content looks like " + looks + "; wrong extension?)";
    }
    fail(file, "not a valid " + format + " file: the " + format + " reader failed" + hint);
  }
  PolygonSoup soup;
  soup.points.resize(3, static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    soup.points.col(static_cast<Eigen::Index>(i)) << points[i].x(), points[i].y(), points[i].z();
  }
  soup.polygons.reserve(polygons.size());
  for (const auto& poly : polygons) {
    std::vector<int> out;
    out.reserve(poly.size());
    for (std::size_t v : poly) {
      // Out-of-range indices are counted by the caller; this keeps them out of range as ints.
      out.push_back(v < points.size() ? static_cast<int>(v) : -1);
    }
    soup.polygons.push_back(std::move(out));
  }
  return soup;
}

}  // namespace

PolygonSoup read_mesh_file(const fs::path& file, const ReadOptions& options) {
  if (!(options.scale > 0) || !std::isfinite(options.scale)) {
    std::ostringstream s;
    s << "scale must be a positive finite number (got " << options.scale << ")";
    fail(file, s.str());
  }
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
    fail(file, "cannot open file (missing or not a regular file)");
  const std::uintmax_t size = fs::file_size(file, ec);
  if (ec) fail(file, "cannot open file");
  if (size == 0) fail(file, "empty file (0 bytes)");
  if (size > kMaxMeshBytes) {
    fail(file, std::to_string(size) + " bytes, more than the " +
                   std::to_string(kMaxMeshBytes >> 20) + " MiB a mesh file may have");
  }

  const std::string ext = lower(file.extension().string());
  const std::string name = file.string();
  PolygonSoup soup;
  if (ext == ".off" || ext == ".ply") {
    const std::string bytes = read_head(file, static_cast<std::size_t>(size));
    if (bytes.size() != size) fail(file, "cannot read the whole file");
    soup = ext == ".off" ? read_off(name, bytes) : read_ply(name, bytes);
  } else if (ext == ".stl" || ext == ".obj") {
    soup = read_with_cgal(file, ext == ".stl" ? "STL" : "OBJ", size);
  } else {
    const std::string looks = sniff_format(read_head(file, 64));
    fail(file, "unknown mesh format \"" + file.extension().string() +
                   "\" (expected .stl, .obj, .ply or .off" +
                   (looks.empty() ? ")" : "; the content looks like " + looks + ")"));
  }
  if (soup.polygons.empty()) {
    fail(file, "no faces (" + std::to_string(soup.points.cols()) + " vertices)");
  }
  const std::size_t nonfinite =
      static_cast<std::size_t>((!soup.points.array().isFinite()).colwise().any().count());
  if (nonfinite > 0) {
    fail(file, std::to_string(nonfinite) + " vertices with NaN or infinite coordinates");
  }
  soup.points *= options.scale;
  std::size_t bad_index = 0, too_small = 0;
  for (const auto& poly : soup.polygons) {
    if (poly.size() < 3) ++too_small;
    for (int v : poly)
      if (v < 0 || v >= soup.points.cols()) ++bad_index;
  }
  if (bad_index > 0) {
    fail(file, std::to_string(bad_index) + " face vertex indices out of range (the file has " +
                   std::to_string(soup.points.cols()) + " vertices)");
  }
  if (too_small > 0) fail(file, std::to_string(too_small) + " faces with fewer than 3 vertices");
  return soup;
}

}  // namespace asperity::geometry
