// The XML VTK writer's pieces that need no VTK to check (io/vtk_xml.hpp); the documents
// themselves are loaded by VTK's own readers in tests/io/check_vtk_series.py.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "solver/io/vtk_xml.hpp"

namespace asperity::io::vtk {
namespace {

std::string b64(const char* s) {
  return base64(s, std::strlen(s));
}

// RFC 4648 §10 test vectors: every padding case.
TEST(VtkXml, Base64MatchesRfc4648Vectors) {
  EXPECT_EQ(b64(""), "");
  EXPECT_EQ(b64("f"), "Zg==");
  EXPECT_EQ(b64("fo"), "Zm8=");
  EXPECT_EQ(b64("foo"), "Zm9v");
  EXPECT_EQ(b64("foob"), "Zm9vYg==");
  EXPECT_EQ(b64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(b64("foobar"), "Zm9vYmFy");
}

// ASCII doubles are written with 17 significant digits: they read back bit for bit.
TEST(VtkXml, AsciiRoundTripsDoubles) {
  Eigen::Matrix3Xd x(3, 4);
  x << 0.1, 1.0 / 3, -2e-300, 7, 1e300, 0, 0, 1, 2, 3, 4, 5;
  Eigen::Matrix4Xi t(4, 1);
  t << 0, 1, 2, 3;
  const std::string xml = unstructured_grid(x, t, {}, {}, Encoding::ascii);
  const auto at = xml.find("Name=\"Points\"");
  ASSERT_NE(at, std::string::npos);
  std::istringstream in(xml.substr(xml.find('>', at) + 1));
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    for (int c = 0; c < 3; ++c) {
      double v = 0;
      in >> v;
      EXPECT_EQ(v, x(c, i));
    }
  }
}

// A series encodes its cells and body ids once (tet_cells, encoded) and copies them into every
// frame: the document must be byte for byte the one written from the plain arrays, in both
// encodings (each appended block stands alone, so only its offset depends on where it goes).
TEST(VtkXml, EncodedOnceEqualsEncodedInPlace) {
  Eigen::Matrix3Xd x(3, 5);
  x << 0, 1, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 0, 1, 1;
  Eigen::Matrix4Xi t(4, 2);
  t << 0, 1, 1, 2, 2, 3, 3, 4;
  const DataArray ids{.name = "body_id", .values = std::vector<std::int32_t>{7, 9}};
  const DataArray vm{.name = "von_mises", .values = std::vector<double>{1.5, -2.25}};
  const DataArray u{.name = "u", .components = 3, .values = std::vector<double>(15, 0.125)};
  for (const Encoding e : {Encoding::base64, Encoding::ascii}) {
    const std::string plain = unstructured_grid(x, t, {u}, {vm, ids}, e);
    const std::string once =
        unstructured_grid(x, tet_cells(t, e), {encoded(u, e)}, {vm, encoded(ids, e)}, e);
    EXPECT_EQ(plain, once);
    EXPECT_THROW(unstructured_grid(x, tet_cells(t, e), {}, {},
                                   e == Encoding::ascii ? Encoding::base64 : Encoding::ascii),
                 std::logic_error);
  }
}

// The collection is sorted by time whatever the order frames were added in (the peak frame is
// added last), and lists exactly what was added.
TEST(VtkXml, CollectionSortedByTime) {
  const auto dir = std::filesystem::temp_directory_path() / "asperity_vtk_xml_test";
  std::filesystem::create_directories(dir);
  Collection c;
  c.add(0.0, "a_0.vtu", 0);
  c.add(2.0, "a_2.vtu", 0);
  c.add(1.5, "peak.vtu", 0);
  c.add(1.5, "fixed.vtu", 1);
  c.write(dir / "run.pvd");
  std::ifstream in(dir / "run.pvd");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto a0 = text.find("a_0.vtu"), peak = text.find("peak.vtu"),
             fixed = text.find("fixed.vtu"), a2 = text.find("a_2.vtu");
  ASSERT_NE(a2, std::string::npos);
  EXPECT_LT(a0, peak);
  EXPECT_LT(peak, fixed);
  EXPECT_LT(fixed, a2);
  EXPECT_EQ(c.size(), 4u);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace asperity::io::vtk
