// Reading every format and every defect class, each with its expected message (issue 3,
// "Validation": a test file per defect, written here into a temporary folder).
#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "solver/core/error.hpp"
#include "solver/geometry/mass_properties.hpp"
#include "solver/geometry/repair_mesh.hpp"
#include "tests/geometry/mesh_fixtures.hpp"

namespace asperity::geometry {
namespace {

using test::load_error;

#define EXPECT_HAS(text, part) EXPECT_NE(std::string(text).find(part), std::string::npos) << (text)

TEST(ReadMesh, EveryFormatGivesTheCube) {
  test::TempDir dir("formats");
  const SurfaceMesh cube = test::unit_cube();
  test::write_text(dir / "cube.off", test::off_text(cube));
  test::write_text(dir / "cube_bin.stl", test::binary_stl(cube));
  std::string ascii_stl = "solid cube\n", obj, ply;
  for (Eigen::Index i = 0; i < cube.faces.cols(); ++i) {
    ascii_stl += "facet normal 0 0 0\nouter loop\n";
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d p = cube.vertices.col(cube.faces(c, i));
      ascii_stl += "vertex " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " +
                   std::to_string(p.z()) + "\n";
    }
    ascii_stl += "endloop\nendfacet\n";
  }
  ascii_stl += "endsolid cube\n";
  test::write_text(dir / "cube_ascii.STL", ascii_stl);
  // OBJ with quads (fan-triangulated on reading), 1-based indices.
  obj = "# cube\n";
  for (Eigen::Index v = 0; v < 8; ++v)
    obj += "v " + std::to_string(cube.vertices(0, v)) + " " + std::to_string(cube.vertices(1, v)) +
           " " + std::to_string(cube.vertices(2, v)) + "\n";
  obj += "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  test::write_text(dir / "cube.obj", obj);
  ply =
      "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float "
      "z\n"
      "element face 12\nproperty list uchar int vertex_indices\nend_header\n";
  std::string body = test::off_text(cube);
  body = body.substr(body.find('\n', 4) + 1);  // the OFF body is the PLY body
  test::write_text(dir / "cube.ply", ply + body);
  // Binary little-endian PLY.
  std::string bply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 8\nproperty double x\n"
      "property double y\nproperty double z\nelement face 12\n"
      "property list uchar int vertex_indices\nend_header\n";
  for (Eigen::Index v = 0; v < 8; ++v)
    bply.append(reinterpret_cast<const char*>(cube.vertices.col(v).data()), 24);
  for (Eigen::Index i = 0; i < 12; ++i) {
    bply += '\3';
    bply.append(reinterpret_cast<const char*>(cube.faces.col(i).data()), 12);
  }
  test::write_text(dir / "cube_bin.ply", bply);

  for (const char* name :
       {"cube.off", "cube_bin.stl", "cube_ascii.STL", "cube.obj", "cube.ply", "cube_bin.ply"}) {
    SCOPED_TRACE(name);
    MeshLog log;
    const SurfaceMesh m = load_surface_mesh(dir / name, {.scale = 1e-3}, log);
    EXPECT_EQ(m.faces.cols(), 12);
    EXPECT_EQ(m.vertices.cols(), 8);
    EXPECT_TRUE(check_mesh(m).valid());
    // A 1 mm cube read with scale 1e-3: 1e-9 m³. The ASCII files hold 6 digits, exact for 0 and 1.
    EXPECT_NEAR(mass_properties(m).volume, 1e-9, 1e-21);
  }
  MeshLog log;
  load_surface_mesh(dir / "cube.obj", {}, log);
  ASSERT_EQ(log.repairs.size(), 1u);
  EXPECT_EQ(log.repairs[0], "fan-triangulated 6 polygons");
}

// The readers silence std::cerr while CGAL parses (read_mesh.cpp); the study reads meshes on
// several threads at once. However the reads interleave, std::cerr must end with its own buffer
// (a swapped-in sink restored by the wrong thread is destroyed with it, and the next write to
// std::cerr, at the latest its flush at exit, crashes).
TEST(ReadMesh, ConcurrentReadsLeaveStdCerrItsBuffer) {
  test::TempDir dir("concurrent");
  test::write_text(dir / "cube.off", test::off_text(test::unit_cube()));
  std::streambuf* const before = std::cerr.rdbuf();
  std::vector<std::thread> pool;
  for (int t = 0; t < 4; ++t) {
    pool.emplace_back([&] {
      for (int k = 0; k < 200; ++k) EXPECT_EQ(load_error(dir / "cube.off"), "");
    });
  }
  for (std::thread& t : pool) t.join();
  EXPECT_EQ(std::cerr.rdbuf(), before);
}

TEST(ReadMesh, EmptyFile) {
  test::TempDir dir("empty");
  test::write_text(dir / "x.stl", "");
  EXPECT_EQ(load_error(dir / "x.stl"), (dir / "x.stl").string() + ": empty file (0 bytes)");
}

TEST(ReadMesh, MissingFile) {
  test::TempDir dir("missing");
  EXPECT_HAS(load_error(dir / "nothing.off"), "cannot open file");
}

TEST(ReadMesh, UnknownExtension) {
  test::TempDir dir("ext");
  test::write_text(dir / "cube.xyz", test::off_text(test::unit_cube()));
  const std::string e = load_error(dir / "cube.xyz");
  EXPECT_HAS(e,
             "unknown mesh format \".xyz\" (expected .stl, .obj, .ply or .off; the content looks "
             "like OFF)");
}

TEST(ReadMesh, WrongExtension) {
  test::TempDir dir("wrongext");
  test::write_text(dir / "cube.ply", test::off_text(test::unit_cube()));
  EXPECT_HAS(
      load_error(dir / "cube.ply"),
      "not a valid PLY file: it does not start with the line \"ply\" (the content looks like OFF; "
      "wrong extension?)");
}

TEST(ReadMesh, TruncatedBinaryStl) {
  test::TempDir dir("truncated");
  test::write_text(dir / "x.stl", test::binary_stl(test::unit_cube(), 7));
  EXPECT_HAS(load_error(dir / "x.stl"),
             "truncated binary STL: header declares 12 triangles (684 bytes) but the file has 434 "
             "bytes (7 whole triangles)");
  test::write_text(dir / "short.stl", std::string(40, '\1'));
  EXPECT_HAS(load_error(dir / "short.stl"),
             "truncated binary STL: 40 bytes, shorter than the 84-byte header");
}

TEST(ReadMesh, NanAndInfiniteCoordinates) {
  test::TempDir dir("nan");
  SurfaceMesh cube = test::unit_cube();
  cube.vertices(0, 3) = std::numeric_limits<double>::quiet_NaN();
  cube.vertices(2, 5) = std::numeric_limits<double>::infinity();
  test::write_text(dir / "x.stl", test::binary_stl(cube));
  // Vertices 3 and 5 are each in several triangles; STL keeps one point per distinct value.
  EXPECT_HAS(load_error(dir / "x.stl"), "vertices with NaN or infinite coordinates");
  std::string off = test::off_text(test::unit_cube());
  off.replace(off.find("\n0 0 0\n"), 7, "\nnan 0 inf\n");
  test::write_text(dir / "x.off", off);
  EXPECT_HAS(load_error(dir / "x.off"), "2 NaN or infinite coordinate values");
}

TEST(RepairMesh, OpenMesh) {
  test::TempDir dir("open");
  SurfaceMesh cube = test::unit_cube();
  SurfaceMesh open = cube;
  open.faces = cube.faces.leftCols(11);  // one triangle missing: a hole with 3 border edges
  test::write_text(dir / "x.off", test::off_text(open));
  EXPECT_EQ(load_error(dir / "x.off"),
            (dir / "x.off").string() + ": open mesh: 3 border edges in 1 hole");
}

TEST(RepairMesh, NonManifoldEdge) {
  test::TempDir dir("nmedge");
  // Two cubes sharing one edge: x = 1, y = 1 is the edge (1,1,z) of both.
  const SurfaceMesh two =
      test::merged(test::unit_cube(), test::translated(test::unit_cube(), {1, 1, 0}));
  test::write_text(dir / "x.off", test::off_text(two));
  // Duplicate vertices merge first (2 shared corners), then the shared edge has 4 faces.
  EXPECT_HAS(load_error(dir / "x.off"),
             "non-manifold edge: 1 edge is shared by more than two faces");
}

TEST(RepairMesh, NonManifoldVertex) {
  test::TempDir dir("nmvertex");
  const SurfaceMesh two =
      test::merged(test::unit_cube(), test::translated(test::unit_cube(), {1, 1, 1}));
  test::write_text(dir / "x.off", test::off_text(two));
  EXPECT_HAS(load_error(dir / "x.off"),
             "non-manifold vertex: at 1 vertex separate sheets of faces touch");
}

TEST(RepairMesh, InvertedMeshIsFlippedAndRecorded) {
  test::TempDir dir("inverted");
  test::write_text(dir / "x.off", test::off_text(test::flipped(test::unit_cube())));
  MeshLog log;
  const SurfaceMesh m = load_surface_mesh(dir / "x.off", {}, log);
  ASSERT_EQ(log.repairs.size(), 1u);
  EXPECT_EQ(log.repairs[0], "flipped the inward-wound mesh (signed volume was -1 m^3)");
  EXPECT_TRUE(check_mesh(m).valid());
}

TEST(RepairMesh, InconsistentFacesAreReoriented) {
  test::TempDir dir("inconsistent");
  SurfaceMesh cube = test::unit_cube();
  std::swap(cube.faces(1, 4), cube.faces(2, 4));
  std::swap(cube.faces(1, 9), cube.faces(2, 9));
  test::write_text(dir / "x.off", test::off_text(cube));
  MeshLog log;
  const SurfaceMesh m = load_surface_mesh(dir / "x.off", {}, log);
  ASSERT_EQ(log.repairs.size(), 1u);
  EXPECT_EQ(log.repairs[0], "reoriented 2 faces to match their neighbours");
  EXPECT_TRUE(check_mesh(m).valid());
}

TEST(RepairMesh, DuplicateVerticesAndDegenerateFacesAreRemoved) {
  test::TempDir dir("dup");
  // The cube with its 8 corners stored 3 times each (as a triangle soup) plus one face with a
  // repeated vertex and one duplicate face.
  const SurfaceMesh cube = test::unit_cube();
  SurfaceMesh soup;
  soup.vertices.resize(3, 36);
  soup.faces.resize(3, 14);
  for (int i = 0; i < 12; ++i)
    for (int c = 0; c < 3; ++c) {
      soup.vertices.col(3 * i + c) = cube.vertices.col(cube.faces(c, i));
      soup.faces(c, i) = 3 * i + c;
    }
  soup.faces.col(12) = Eigen::Vector3i(0, 0, 1);
  soup.faces.col(13) = soup.faces.col(5);
  test::write_text(dir / "x.off", test::off_text(soup));
  MeshLog log;
  const SurfaceMesh m = load_surface_mesh(dir / "x.off", {}, log);
  EXPECT_EQ(m.vertices.cols(), 8);
  EXPECT_EQ(m.faces.cols(), 12);
  ASSERT_EQ(log.repairs.size(), 3u);
  EXPECT_EQ(log.repairs[0], "merged 28 duplicate vertices");
  EXPECT_EQ(log.repairs[1], "removed 1 degenerate face with a repeated vertex");
  EXPECT_EQ(log.repairs[2], "removed 1 duplicate face");
}

TEST(RepairMesh, TinyShellIsDroppedWithAWarningAndALargeOneRefused) {
  test::TempDir dir("shells");
  // A 0.1-wide cube inside the unit cube: 0.1 % of its volume, below kTinyShellFraction.
  const SurfaceMesh bubble = test::box({0.45, 0.45, 0.45}, {0.55, 0.55, 0.55});
  test::write_text(dir / "tiny.off", test::off_text(test::merged(test::unit_cube(), bubble)));
  MeshLog log;
  const SurfaceMesh m = load_surface_mesh(dir / "tiny.off", {}, log);
  EXPECT_EQ(m.faces.cols(), 12);
  ASSERT_EQ(log.warnings.size(), 1u);
  EXPECT_HAS(log.warnings[0], "dropped a tiny shell of 12 faces (volume 0.1% of the main shell)");
  EXPECT_EQ(log.repairs, log.warnings);

  test::write_text(dir / "two.off",
                   test::off_text(test::merged(test::unit_cube(),
                                               test::translated(test::unit_cube(), {3, 0, 0}))));
  EXPECT_HAS(load_error(dir / "two.off"),
             "several shells: 2 separate closed surfaces, 1 of them larger than 1% of the largest");
}

TEST(RepairMesh, SelfIntersection) {
  test::TempDir dir("selfint");
  // A cube whose top corner (1,1,1) is pushed down through the bottom: its faces cross others.
  SurfaceMesh cube = test::unit_cube();
  cube.vertices.col(7) = Eigen::Vector3d(0.9, 0.9, -0.5);
  test::write_text(dir / "x.off", test::off_text(cube));
  EXPECT_HAS(load_error(dir / "x.off"), "self-intersecting surface:");
}

TEST(RepairMesh, ZeroVolume) {
  test::TempDir dir("flat");
  // A closed, manifold, consistently oriented tetrahedron whose four corners lie in one plane.
  SurfaceMesh flat;
  flat.vertices.resize(3, 4);
  flat.vertices << 0, 1, 0, 0.3, 0, 0, 1, 0.3, 0, 0, 0, 0;
  flat.faces.resize(3, 4);
  flat.faces << 0, 0, 0, 1, 2, 1, 3, 2, 1, 3, 2, 3;
  test::write_text(dir / "x.off", test::off_text(flat));
  EXPECT_HAS(load_error(dir / "x.off"),
             "zero volume (0 m^3 inside a 1 m bounding box): a flat or collapsed surface");
}

TEST(CheckMesh, CountsWithoutRepairing) {
  SurfaceMesh open = test::unit_cube();
  open.faces = open.faces.leftCols(10).eval();
  const MeshCheck c = check_mesh(open);
  EXPECT_FALSE(c.closed());
  EXPECT_EQ(c.border_edges, 4);
  EXPECT_EQ(c.shells, 1);
  EXPECT_FALSE(c.valid());
  const MeshCheck inverted = check_mesh(test::flipped(test::unit_cube()));
  EXPECT_TRUE(inverted.closed());
  EXPECT_NEAR(inverted.volume, -1.0, 1e-15);
  EXPECT_FALSE(inverted.valid());
}

}  // namespace
}  // namespace asperity::geometry
