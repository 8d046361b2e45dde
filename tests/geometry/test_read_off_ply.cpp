// Our own OFF and PLY readers (read_off.cpp, read_ply.cpp): the committed meshes read as an
// independent naive parser reads them and survive every PLY encoding bit for bit; every malformed
// input, the fuzzers' regression seeds included, is one InputError line naming the file, the
// place and the problem.
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "solver/core/error.hpp"
#include "solver/geometry/read_mesh.hpp"
#include "solver/geometry/read_off.hpp"
#include "solver/geometry/read_ply.hpp"

namespace asperity::geometry {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The message of the InputError that reading BYTES throws, or "" when it reads.
template <class Reader>
std::string error_of(Reader read, const std::string& bytes, const std::string& file = "m") {
  try {
    read(file, bytes);
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.find('\n'), std::string::npos) << "one line";
    EXPECT_EQ(m.rfind(file + ": ", 0), 0u) << "names the file: " << m;
    return m;
  }
  return "";
}
std::string off_error(const std::string& bytes) {
  return error_of(read_off, bytes, "m.off");
}
std::string ply_error(const std::string& bytes) {
  return error_of(read_ply, bytes, "m.ply");
}

#define EXPECT_HAS(text, part) EXPECT_NE(std::string(text).find(part), std::string::npos) << (text)

// An independent reading of a well-formed OFF (the committed files): stream extraction, no checks.
PolygonSoup naive_off(const std::string& bytes) {
  std::istringstream in(bytes);
  std::string keyword;
  std::size_t nv = 0, nf = 0, ne = 0;
  in >> keyword >> nv >> nf >> ne;
  PolygonSoup s;
  s.points.resize(3, static_cast<Eigen::Index>(nv));
  for (std::size_t v = 0; v < nv; ++v)
    for (int c = 0; c < 3; ++c) in >> s.points(c, static_cast<Eigen::Index>(v));
  for (std::size_t f = 0; f < nf; ++f) {
    std::size_t n = 0;
    in >> n;
    std::vector<int> p(n);
    for (int& i : p) in >> i;
    s.polygons.push_back(p);
  }
  return s;
}

void expect_same(const PolygonSoup& a, const PolygonSoup& b) {
  ASSERT_EQ(a.points.cols(), b.points.cols());
  // Exact: 17 significant digits round-trip a double, and from_chars rounds correctly.
  EXPECT_EQ((a.points - b.points).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(a.polygons, b.polygons);
}

// PLY of SOUP in FORMAT (ascii, binary_little_endian, binary_big_endian), coordinates as
// COORD (float or double), faces as a list of COUNT-type / INDEX-type, with an extra vertex
// property, an extra face list and an extra element before and after, all to be skipped.
template <class Coord, class Count, class Index>
std::string ply_of(const PolygonSoup& soup, const std::string& format, const std::string& coord,
                   const std::string& count, const std::string& index) {
  std::ostringstream h;
  h << "ply\nformat " << format << " 1.0\ncomment written by the test\n"
    << "element camera 1\nproperty float f\nproperty list uchar short junk\n"
    << "element vertex " << soup.points.cols() << "\nproperty " << coord << " x\nproperty " << coord
    << " y\nproperty uchar quality\nproperty " << coord << " z\n"
    << "element face " << soup.polygons.size() << "\nproperty list " << count << " " << index
    << " vertex_indices\nproperty list uchar float texcoord\n"
    << "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n";
  std::string s = h.str();
  const bool ascii = format == "ascii";
  const bool swap = (format == "binary_big_endian") == (std::endian::native == std::endian::little);
  const auto put = [&](auto x) {
    if (ascii) {
      std::ostringstream t;
      t.precision(17);
      t << +x << ' ';
      s += t.str();
      return;
    }
    char b[sizeof x];
    std::memcpy(b, &x, sizeof x);
    if (swap)
      for (std::size_t i = 0; i < sizeof x / 2; ++i) std::swap(b[i], b[sizeof x - 1 - i]);
    s.append(b, sizeof x);
  };
  const auto end_line = [&] {
    if (ascii) s += '\n';
  };
  put(1.5f), put(std::uint8_t{2}), put(std::int16_t{-7}), put(std::int16_t{300}), end_line();
  for (Eigen::Index v = 0; v < soup.points.cols(); ++v) {
    put(static_cast<Coord>(soup.points(0, v))), put(static_cast<Coord>(soup.points(1, v)));
    put(std::uint8_t{255}), put(static_cast<Coord>(soup.points(2, v))), end_line();
  }
  for (const auto& p : soup.polygons) {
    put(static_cast<Count>(p.size()));
    for (int i : p) put(static_cast<Index>(i));
    put(std::uint8_t{2}), put(0.25f), put(0.75f), end_line();
  }
  put(std::int32_t{0}), put(std::int32_t{1}), end_line();
  return s;
}

TEST(ReadOff, CommittedMeshesReadAsANaiveParserReadsThem) {
  std::vector<fs::path> files = {fs::path(ASPERITY_DATA_DIR) / "meshes/particle-seed3-320.off"};
  for (const auto& e : fs::directory_iterator(fs::path(ASPERITY_DATA_DIR) / "meshes/convex"))
    if (e.path().extension() == ".off") files.push_back(e.path());
  ASSERT_GE(files.size(), 5u);
  for (const fs::path& f : files) {
    SCOPED_TRACE(f.string());
    const std::string bytes = slurp(f);
    const PolygonSoup ours = read_off(f.string(), bytes);
    EXPECT_GT(ours.polygons.size(), 0u);
    expect_same(ours, naive_off(bytes));
  }
}

TEST(ReadPly, EveryEncodingAndTypeGivesTheSameSoup) {
  const fs::path f = fs::path(ASPERITY_DATA_DIR) / "meshes/particle-seed3-320.off";
  const PolygonSoup soup = read_off(f.string(), slurp(f));
  ASSERT_EQ(soup.polygons.size(), 320u);
  for (const char* format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
    SCOPED_TRACE(format);
    expect_same(read_ply("d.ply", ply_of<double, std::uint8_t, std::int32_t>(soup, format, "double",
                                                                             "uchar", "int")),
                soup);
    expect_same(read_ply("d.ply", ply_of<double, std::int32_t, std::uint32_t>(
                                      soup, format, "float64", "int32", "uint32")),
                soup);
    // float coordinates: the soup's own values rounded to float, exactly.
    PolygonSoup rounded = soup;
    rounded.points = soup.points.cast<float>().cast<double>();
    expect_same(read_ply("f.ply", ply_of<float, std::uint16_t, std::uint16_t>(soup, format, "float",
                                                                              "ushort", "ushort")),
                rounded);
  }
}

TEST(ReadOff, VariantsCommentsAndHomogeneousCoordinates) {
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const PolygonSoup plain = read_off("t.off", "OFF\n4 4 6\n" + body);
  ASSERT_EQ(plain.polygons.size(), 4u);
  // Comments, blank lines, CRLF, counts on the keyword line, colours and normals ignored.
  expect_same(read_off("t.off", "# tetrahedron\r\nOFF 4 4 6 # counts\r\n\r\n" + body), plain);
  expect_same(read_off("t.off",
                       "COFF\n4 4 6\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 1 1 1 1\n"
                       "0 0 1 0 0 0 0\n3 0 2 1 1 0 0\n3 0 1 3\n3 0 3 2 0.5 0.5 0.5 1\n3 1 2 3\n"),
              plain);
  expect_same(read_off("t.off",
                       "NOFF\n4 4 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n"
                       "0 0 1 0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"),
              plain);
  // 4OFF: (x, y, z, w) is the point (x/w, y/w, z/w).
  expect_same(read_off("t.off",
                       "4OFF\n4 4 6\n0 0 0 2\n2 0 0 2\n0 0.5 0 0.5\n0 0 -1 -1\n"
                       "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"),
              plain);
}

TEST(ReadOff, MalformedFilesAreOneLineEach) {
  const std::string verts = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  EXPECT_HAS(off_error("OFF BINARY\n4 4 6\n"), "m.off: OFF line 1 (header): binary OFF is not");
  EXPECT_HAS(off_error("nOFF\n3\n"), "nOFF (a dimension other than 3) is not supported");
  EXPECT_HAS(off_error("ply\nformat ascii 1.0\n"),
             "m.off: not a valid OFF file: line 1 should start with the keyword OFF (or COFF, "
             "NOFF, STOFF, 4OFF), not \"ply\" (the content looks like PLY; wrong extension?)");
  EXPECT_HAS(off_error("OFF\n-4 4 6\n" + verts),
             "m.off: OFF header: vertex and face counts must be whole numbers below 2^40 (got "
             "\"-4\", \"4\", line 2)");
  EXPECT_HAS(off_error("OFF\n2000000000 1 0\n0 0 0\n"),
             "m.off: OFF header declares 2000000000 vertices and 1 faces, which need at least "
             "12000000008 bytes; 6 follow the header (line 2)");
  EXPECT_HAS(off_error("OFF\n4 1 0\n" + verts + "# no faces follow\n"),
             "OFF: the file ends after 0 of 1 faces");
  EXPECT_HAS(off_error("OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 x\n0 0 1\n3 0 1 2\n"),
             "m.off: OFF line 5 (vertex 2): \"x\" is not a number");
  EXPECT_HAS(off_error("OFF\n4 1 0\n0 0 0\n1 0\n0 1 0\n0 0 1\n3 0 1 2\n# pad\n"),
             "OFF line 4 (vertex 1): 2 coordinates, expected 3");
  EXPECT_HAS(off_error("OFF\n4 1 0\n" + verts + "3 0 1 4\n"),
             "m.off: OFF line 7 (face 0): vertex index 4 out of range (the file has 4 vertices)");
  EXPECT_HAS(off_error("OFF\n4 1 0\n" + verts + "3 0 -1 2\n"), "vertex index -1 out of range");
  EXPECT_HAS(off_error("OFF\n4 1 0\n" + verts + "2 0 1\n# pad\n"),
             "OFF line 7 (face 0): 2 vertices; a face needs at least 3");
  EXPECT_HAS(off_error("OFF\n4 1 0\nnan 0 0\n1 inf 0\n0 1 -inf\n0 0 1\n3 0 1 2\n"),
             "m.off: 3 NaN or infinite coordinate values (OFF, the first on line 3)");
  // 4OFF with w = 0 is a point at infinity.
  EXPECT_HAS(off_error("4OFF\n3 1 0\n0 0 0 1\n1 0 0 0\n0 1 0 1\n3 0 1 2\n"),
             "3 NaN or infinite coordinate values");
}

// The two crash classes of CI round 2, rebuilt: a face line whose count is huge, negative or
// binary garbage (CGAL resized the index list to it: allocation-size-too-big under ASan).
TEST(ReadOff, FaceCountsAreBoundedByTheirLine) {
  const std::string head = "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  EXPECT_HAS(off_error(head + "39322604862016 0 1 2\n"),
             "m.off: OFF line 7 (face 0): declares 39322604862016 vertices but the line holds 3 "
             "numbers after the count");
  EXPECT_HAS(off_error(head + "-69 0 1 2\n"),
             "OFF line 7 (face 0): -69 vertices; a face needs at least 3");
  EXPECT_HAS(off_error(head + "3\273\377\377\377 0 1 2\n"),
             "OFF line 7 (face 0): vertex count \"3????\" is not a whole number");
  EXPECT_HAS(off_error(head + "99999999999999999999999 0 1 2\n"), "is not a whole number");
}

TEST(ReadPly, MalformedHeadersAreOneLineEach) {
  const std::string v = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  const std::string f = "element face 1\nproperty list uchar int vertex_indices\n";
  const std::string data = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  ASSERT_EQ(ply_error("ply\nformat ascii 1.0\n" + v + f + "end_header\n" + data), "");
  EXPECT_HAS(ply_error("OFF\n3 1 0\n"),
             "m.ply: not a valid PLY file: it does not start with the "
             "line \"ply\" (the content looks like OFF; wrong "
             "extension?)");
  EXPECT_HAS(ply_error("ply\nformat ascii 1.0\nproperty float x\n" + v + f + "end_header\n"),
             "m.ply: PLY header line 3: a property before any element");
  EXPECT_HAS(ply_error("ply\nformat ascii 1.0\n" + v + f), "m.ply: PLY header without end_header");
  EXPECT_HAS(ply_error("ply\n" + v + f + "end_header\n" + data), "PLY header without a format");
  EXPECT_HAS(ply_error("ply\nformat binary_middle_endian 1.0\n" + v + f + "end_header\n"),
             "PLY header line 2: unknown format \"binary_middle_endian\"");
  EXPECT_HAS(ply_error("ply\nformat ascii 1.0\nelement vertex -3\n"),
             "PLY header line 3: element \"vertex\": the count must be a whole number below 2^40 "
             "(got \"-3\")");
  EXPECT_HAS(ply_error("ply\nformat ascii 1.0\n" + v + "property quad w\n"),
             "PLY header line 7: unknown property type \"quad\"");
  EXPECT_HAS(ply_error("ply\nformat ascii 1.0\n" + v +
                       "element face 1\n"
                       "property list float int vertex_indices\n"),
             "PLY header line 8: list count type \"float\" is not an integer type");
  EXPECT_HAS(ply_error("ply\nformat ascii 1.0\n" + v + v), "element \"vertex\" declared twice");
  std::string many = "ply\nformat ascii 1.0\n";
  for (int i = 0; i < 101; ++i) many += "element e" + std::to_string(i) + " 0\n";
  EXPECT_HAS(ply_error(many), "PLY header line 103: more than 100 elements");
  std::string wide = "ply\nformat ascii 1.0\nelement vertex 0\n";
  for (int i = 0; i < 1001; ++i) wide += "property float p" + std::to_string(i) + "\n";
  EXPECT_HAS(ply_error(wide),
             "PLY header line 1004: element \"vertex\" has more than 1000 properties");
  EXPECT_HAS(ply_error("ply\nformat ascii 1.0\nelenmet vertex 3\n"),
             "PLY header line 3: unknown keyword \"elenmet\"");
  EXPECT_HAS(ply_error("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n" + f +
                       "end_header\n" + data),
             "m.ply: PLY element \"vertex\" has no scalar property y");
  EXPECT_HAS(ply_error("ply\nformat ascii 1.0\n" + v +
                       "element face 1\nproperty list uchar int indices\nend_header\n" + data),
             "PLY element \"face\" has no list property vertex_indices (or vertex_index)");
  EXPECT_HAS(ply_error("ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\n"
                       "property float x\nproperty float y\nproperty float z\n" +
                       f + "end_header\n"),
             "m.ply: PLY header declares 1000000000 vertices and 1 faces, which need at least "
             "12000000000 bytes (up to element \"vertex\"); 0 follow the header");
}

TEST(ReadPly, MalformedDataIsOneLineEach) {
  const std::string h =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  const std::string verts = "0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_HAS(ply_error(h + verts + "3 0 1 3\n"),
             "m.ply: PLY element \"face\" 0 (line 13): vertex index 3 out of range (the header "
             "declares 3 vertices)");
  EXPECT_HAS(ply_error(h + verts + "2 0 1\n"), "\"face\" 0 (line 13): 2 vertices; a face needs");
  EXPECT_HAS(ply_error(h + verts + "3 0 1\n"),
             "PLY element \"face\" 0 (line 13): list \"vertex_indices\" declares 3 items; 5 bytes "
             "are left");
  EXPECT_HAS(ply_error(h + "0.000 0 0\n1.000 0 0\n0 1\n"),
             "PLY element \"vertex\" 2 (line 13): the file ends early");
  EXPECT_HAS(ply_error(h + "0 0 0\n1 0 0\n0 one 0\n3 0 1 2\n"),
             "PLY element \"vertex\" 2 (line 12): \"one\" is not a number");
  EXPECT_HAS(ply_error(h + verts + "3 0 1.5 2\n"),
             "\"face\" 0 (line 13): vertex index \"1.5\" is not a whole number");
  EXPECT_HAS(ply_error(h + "nan 0 0\n1 0 0\n0 1 inf\n3 0 1 2\n"),
             "m.ply: 2 NaN or infinite coordinate values (PLY, the first in PLY element "
             "\"vertex\" 0 (line 10))");
}

// The list-count crash class of CI round 2, rebuilt: a count that is negative, huge, or larger
// than the bytes left (CGAL sized a buffer from it: UBSan offset 18446744073709551552 = -64).
TEST(ReadPly, ListCountsAreBoundedByTheBytesLeft) {
  const auto binary = [](const std::string& count_type, const std::string& tail) {
    std::string s =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nelement face 1\nproperty list " +
        count_type + " int vertex_indices\nend_header\n";
    s += std::string(36, '\0');  // three vertices at the origin
    return s + tail;
  };
  const std::string minus64("\xc0\xff\xff\xff", 4);
  const std::string indices("\0\0\0\0\1\0\0\0\2\0\0\0", 12);
  EXPECT_EQ(ply_error(binary("int", std::string("\3\0\0\0", 4) + indices)), "");
  // The count is the 4 bytes after the header and the three 12-byte vertices.
  const std::string with_count = binary("int", minus64 + indices);
  const std::size_t at = with_count.find("end_header\n") + 11 + 36;
  EXPECT_HAS(ply_error(with_count), "m.ply: PLY element \"face\" 0 (byte " +
                                        std::to_string(at + 4) +
                                        "): list \"vertex_indices\" declares -64 items; 12 bytes "
                                        "are left");
  EXPECT_HAS(ply_error(binary("uint", minus64 + indices)),
             "list \"vertex_indices\" declares 4294967232 items; 12 bytes are left");
  EXPECT_HAS(ply_error(binary("uchar", "\4" + indices)),
             "list \"vertex_indices\" declares 4 items; 12 bytes are left");
  EXPECT_HAS(ply_error(binary("int", std::string("\3\0\0\0", 4) + indices.substr(0, 8))),
             "declares 3 items; 8 bytes are left");
  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list int int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_HAS(ply_error(ascii + "-64 0 1 2\n"),
             "PLY element \"face\" 0 (line 13): list \"vertex_indices\" declares -64 items");
  EXPECT_HAS(ply_error(ascii + "4294967232 0 1 2\n"), "declares 4294967232 items; 7 bytes");
  EXPECT_HAS(ply_error(ascii + "18446744073709551552 0 1 2\n"),
             "list count \"18446744073709551552\" is not a whole number");
}

// An element without properties takes no bytes, so its count (here 2^40 − 1, the largest the
// header allows) reads nothing: the tetrahedron after it is read whole, at once. Before, the
// reader looped over the items (a timeout of fuzz_mesh_ply's one-hour run; at 2^40 items this
// test would run for hours and fail on ctest's timeout).
TEST(ReadPly, AnElementWithoutPropertiesReadsNothingWhateverItsCount) {
  for (const char* format : {"ascii", "binary_little_endian"}) {
    SCOPED_TRACE(format);
    std::string s = std::string("ply\nformat ") + format +
                    " 1.0\nelement padding 1099511627775\nelement vertex 4\nproperty float x\n"
                    "property float y\nproperty float z\nelement face 1\n"
                    "property list uchar int vertex_indices\nend_header\n";
    if (std::string(format) == "ascii") {
      s += "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n";
    } else {
      const float xyz[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
      s.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
      s += std::string("\3\0\0\0\0\2\0\0\0\1\0\0\0", 13);
    }
    const PolygonSoup soup = read_ply("p.ply", s);
    EXPECT_EQ(soup.points.cols(), 4);
    ASSERT_EQ(soup.polygons.size(), 1u);
    EXPECT_EQ(soup.polygons[0], (std::vector<int>{0, 2, 1}));
  }
}

// Every committed fuzz seed of the two formats, the regression inputs among them, is a soup or
// one InputError line through the whole reading path (read_mesh_file).
TEST(ReadOffPly, FuzzSeedsEndInASoupOrOneLine) {
  const fs::path corpus = ASPERITY_FUZZ_CORPUS;
  std::size_t seeds = 0, refused = 0, regressions = 0;
  for (const char* format : {"off", "ply"}) {
    for (const auto& e : fs::directory_iterator(corpus / format)) {
      SCOPED_TRACE(e.path().string());
      const fs::path copy = fs::temp_directory_path() /
                            ("asperity-seed-" + e.path().filename().string() + "." + format);
      fs::copy_file(e.path(), copy, fs::copy_options::overwrite_existing);
      ++seeds;
      const bool regression = e.path().filename().string().rfind("regression-", 0) == 0;
      regressions += regression ? 1 : 0;
      try {
        read_mesh_file(copy);
      } catch (const InputError& err) {
        ++refused;
        const std::string m = err.what();
        EXPECT_EQ(m.rfind(copy.string() + ": ", 0), 0u) << m;
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
        if (!regression) ADD_FAILURE() << "a valid seed is refused: " << m;
      }
      fs::remove(copy);
    }
  }
  EXPECT_GE(seeds, 13u);
  EXPECT_GE(regressions, 9u);  // the crash classes of rounds 1 and 2
  EXPECT_EQ(refused, regressions) << "every regression seed is refused, every other one read";
}

}  // namespace
}  // namespace asperity::geometry
