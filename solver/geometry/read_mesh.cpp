// Reading surface meshes with CGAL's stream I/O; the checks before and after it turn every kind of
// bad file into one line naming the file and the defect (issue 3, "Reading").
#include "geometry/read_mesh.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/OFF.h>
#include <CGAL/IO/PLY.h>
#include <CGAL/IO/STL.h>

#include "core/error.hpp"

namespace asperity::geometry {
namespace {
namespace fs = std::filesystem;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;

[[noreturn]] void fail(const fs::path& file, const std::string& problem) {
  throw InputError(file.string() + ": " + problem);
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string read_head(const fs::path& file, std::size_t n) {
  std::ifstream in(file, std::ios::binary);
  std::string head(n, '\0');
  in.read(head.data(), static_cast<std::streamsize>(n));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return head;
}

// What the first bytes look like, to turn "does not parse" into "wrong extension?".
std::string sniff_format(const std::string& head) {
  std::size_t i = 0;
  while (i < head.size() && std::isspace(static_cast<unsigned char>(head[i]))) ++i;
  const std::string h = lower(head.substr(i, 8));
  if (h.rfind("ply", 0) == 0) return "PLY";
  if (h.rfind("solid", 0) == 0) return "ASCII STL";
  if (h.rfind("off", 0) == 0 || h.rfind("coff", 0) == 0 || h.rfind("noff", 0) == 0) return "OFF";
  if (h.rfind("v ", 0) == 0 || h.rfind("# ", 0) == 0 || h.rfind("o ", 0) == 0 ||
      h.rfind("mtllib", 0) == 0)
    return "OBJ";
  return "";
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

// Header counts checked against the file's size before any reader allocates for them: an OFF or
// PLY header is a promise the reader trusts (CGAL reserves what it declares: 2e9 vertices is a
// std::bad_alloc, 1e8 in a 15 KB file costs 2.3 GB before the file is refused). Every ASCII
// number takes at least two bytes (a digit and a separator).
void check_declared_counts(const fs::path& file, const std::string& format, std::uintmax_t size,
                           std::uintmax_t vertices, std::uintmax_t faces,
                           std::uintmax_t vertex_bytes, std::uintmax_t face_bytes) {
  // Both counts are below 2^40 here (parsed with a cap), so the products do not overflow.
  const std::uintmax_t need = vertices * vertex_bytes + faces * face_bytes;
  if (need > size) {
    fail(file, format + " header declares " + std::to_string(vertices) + " vertices and " +
                   std::to_string(faces) + " faces, which need at least " + std::to_string(need) +
                   " bytes; the file has " + std::to_string(size));
  }
}

// A count token from a header: digits only, below 2^40 (more is refused as absurd).
std::optional<std::uintmax_t> header_count(const std::string& token) {
  if (token.empty() || token.size() > 12 ||
      !std::all_of(token.begin(), token.end(), [](unsigned char c) { return std::isdigit(c); }))
    return std::nullopt;
  return std::stoull(token);
}

void check_off_header(const fs::path& file, std::uintmax_t size) {
  std::ifstream in(file, std::ios::binary);
  std::string token;
  std::vector<std::string> tokens;
  // The keyword, then three counts; '#' starts a comment to the end of the line.
  while (tokens.size() < 4 && in >> token) {
    if (token[0] == '#') {
      std::string rest;
      std::getline(in, rest);
      continue;
    }
    tokens.push_back(token);
  }
  if (tokens.empty()) return;
  const std::string kw = lower(tokens[0]);
  if (kw.find("off") == std::string::npos) return;  // the reader says what is wrong
  if (kw.find("binary") != std::string::npos || tokens.size() < 4) return;
  const auto nv = header_count(tokens[1]), nf = header_count(tokens[2]);
  if (!nv || !nf) {
    fail(file, "OFF header: vertex and face counts must be whole numbers below 2^40 (got \"" +
                   tokens[1].substr(0, 20) + "\", \"" + tokens[2].substr(0, 20) + "\")");
  }
  const std::uintmax_t coords = kw.find('4') != std::string::npos ? 4 : 3;
  check_declared_counts(file, "OFF", size, *nv, *nf, 2 * coords, 2 * 4);
  // Each face line starts with its vertex count, which the reader also trusts (a face of 4e13
  // vertices: found by fuzz_mesh_off); it must fit in the file like the header's counts.
  std::string line;
  std::getline(in, line);  // the rest of the counts line
  const auto content = [](const std::string& l) {
    const std::size_t i = l.find_first_not_of(" \t\r");
    return i != std::string::npos && l[i] != '#';
  };
  for (std::uintmax_t v = 0; v < *nv && std::getline(in, line);) {
    if (content(line)) ++v;
  }
  for (std::uintmax_t f = 0; f < *nf && std::getline(in, line);) {
    if (!content(line)) continue;
    std::istringstream l(line);
    std::string first;
    l >> first;
    const bool digits = !first.empty() && std::all_of(first.begin(), first.end(), [](char c) {
      return std::isdigit(static_cast<unsigned char>(c));
    });
    if (digits && (first.size() > 15 || 2 * std::stoull(first) > size)) {
      fail(file, "OFF face " + std::to_string(f) + " declares " + first +
                     " vertices, more than the file's " + std::to_string(size) + " bytes can hold");
    }
    ++f;
  }
}

void check_ply_header(const fs::path& file, std::uintmax_t size) {
  std::ifstream in(file, std::ios::binary);
  std::string line;
  bool ascii = true;
  std::uintmax_t nv = 0, nf = 0, vertex_bytes = 0;
  std::string element;
  static const std::map<std::string, std::uintmax_t> kBytes = {
      {"char", 1},  {"uchar", 1},   {"int8", 1},   {"uint8", 1},  {"short", 2}, {"ushort", 2},
      {"int16", 2}, {"uint16", 2},  {"int", 4},    {"uint", 4},   {"int32", 4}, {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  bool ended = false, has_format = false;
  std::getline(in, line);
  if (lower(line).rfind("ply", 0) != 0) return;  // not PLY at all: the reader says so, with a hint
  for (int n = 0; n < 1000 && std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream l(line);
    std::string kw;
    l >> kw;
    if (kw == "end_header") {
      ended = true;
      break;
    }
    // CGAL's reader trusts the header's structure (a property before any element indexes an
    // empty list: found by fuzz_mesh_ply), so only the PLY keywords, in order, pass.
    if (kw == "comment" || kw == "obj_info" || kw.empty()) continue;
    if (kw != "format" && kw != "element" && kw != "property") {
      fail(file, "PLY header line " + std::to_string(n + 2) + ": unknown keyword \"" +
                     kw.substr(0, 20) + "\"");
    }
    if (kw == "property" && element.empty()) {
      fail(file, "PLY header line " + std::to_string(n + 2) + ": a property before any element");
    }
    if (kw == "format") has_format = true;
    if (kw == "format") {
      std::string f;
      l >> f;
      ascii = f == "ascii";
    } else if (kw == "element") {
      std::string count;
      l >> element >> count;
      const auto c = header_count(count);
      if (!c) {
        fail(file, "PLY header: element \"" + element.substr(0, 20) +
                       "\" count must be a whole number below 2^40 (got \"" + count.substr(0, 20) +
                       "\")");
      }
      if (element == "vertex") nv = *c;
      if (element == "face") nf = *c;
    } else if (kw == "property" && element == "vertex") {
      std::string type;
      l >> type;
      auto it = kBytes.find(type);
      if (it == kBytes.end() && type != "list") {
        fail(file, "PLY header: unknown property type \"" + type.substr(0, 20) + "\"");
      }
      vertex_bytes += ascii ? 2 : (it == kBytes.end() ? 1 : it->second);
    }
  }
  if (!ended || !has_format) fail(file, "PLY header without format or end_header");
  // A face is at least a count and three indices: 8 bytes in ASCII, 4 in the smallest binary.
  check_declared_counts(file, "PLY", size, nv, nf, std::max<std::uintmax_t>(vertex_bytes, 1),
                        ascii ? 8 : 4);
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

// CGAL's readers print their own diagnostics to std::cerr (e.g. the PLY reader's "incorrect file
// format"); the contract allows one line on stderr, ours, so they are held while reading.
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
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  bool ok = false;
  std::string format;
  const std::string name = file.string();
  std::optional<QuietCerr> quiet(std::in_place);
  if (ext == ".stl") {
    format = "STL";
    check_binary_stl_size(file, size);
    ok = CGAL::IO::read_STL(name, points, polygons);
  } else if (ext == ".obj") {
    format = "OBJ";
    ok = CGAL::IO::read_OBJ(name, points, polygons);
  } else if (ext == ".ply") {
    format = "PLY";
    check_ply_header(file, size);
    ok = CGAL::IO::read_PLY(name, points, polygons);
  } else if (ext == ".off") {
    format = "OFF";
    check_off_header(file, size);
    ok = CGAL::IO::read_OFF(name, points, polygons);
  } else {
    const std::string looks = sniff_format(read_head(file, 64));
    fail(file, "unknown mesh format \"" + file.extension().string() +
                   "\" (expected .stl, .obj, .ply or .off" +
                   (looks.empty() ? ")" : "; the content looks like " + looks + ")"));
  }
  quiet.reset();
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
  if (polygons.empty()) fail(file, "no faces (" + std::to_string(points.size()) + " vertices)");

  PolygonSoup soup;
  soup.points.resize(3, static_cast<Eigen::Index>(points.size()));
  std::size_t nonfinite = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d p(points[i].x(), points[i].y(), points[i].z());
    if (!p.allFinite()) ++nonfinite;
    soup.points.col(static_cast<Eigen::Index>(i)) = options.scale * p;
  }
  if (nonfinite > 0) {
    fail(file, std::to_string(nonfinite) + " vertices with NaN or infinite coordinates");
  }
  soup.polygons.reserve(polygons.size());
  std::size_t bad_index = 0, too_small = 0;
  for (const auto& poly : polygons) {
    if (poly.size() < 3) ++too_small;
    std::vector<int> out;
    out.reserve(poly.size());
    for (std::size_t v : poly) {
      if (v >= points.size()) ++bad_index;
      out.push_back(static_cast<int>(v));
    }
    soup.polygons.push_back(std::move(out));
  }
  if (bad_index > 0) {
    fail(file, std::to_string(bad_index) + " face vertex indices out of range (the file has " +
                   std::to_string(points.size()) + " vertices)");
  }
  if (too_small > 0) fail(file, std::to_string(too_small) + " faces with fewer than 3 vertices");
  return soup;
}

}  // namespace asperity::geometry
