// Mass properties and shape measures against closed-form answers (issue 3, "Validation").
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "solver/geometry/geodesic_sphere.hpp"
#include "solver/geometry/mass_properties.hpp"
#include "solver/geometry/shape_metrics.hpp"
#include "tests/geometry/mesh_fixtures.hpp"

namespace asperity::geometry {
namespace {

// The formulas are exact for polyhedra; 1e-12 relative leaves room for the round-off of a few
// dozen double operations per face (ε ≈ 2e-16) and nothing else.
constexpr double kExact = 1e-12;

void expect_rel(double got, double want, double rel = kExact) {
  EXPECT_NEAR(got, want, rel * std::abs(want)) << got;
}

TEST(MassProperties, UnitCube) {
  const MassProperties m = mass_properties(test::unit_cube());
  expect_rel(m.volume, 1.0);
  for (int d = 0; d < 3; ++d) expect_rel(m.centroid(d), 0.5);
  // Solid cube of side s, mass V: I = V s² / 6 about every centroidal axis.
  for (int d = 0; d < 3; ++d) expect_rel(m.inertia(d, d), 1.0 / 6.0);
  EXPECT_NEAR(m.inertia(0, 1), 0.0, kExact);
  EXPECT_NEAR(m.inertia(0, 2), 0.0, kExact);
  EXPECT_NEAR(m.inertia(1, 2), 0.0, kExact);
  expect_rel(m.equivalent_radius, std::cbrt(3.0 / (4.0 * std::numbers::pi)));
  expect_rel(m.elongation, 1.0);
  expect_rel(m.flatness, 1.0);
}

TEST(MassProperties, BoxFarFromOrigin) {
  // 1 × 2 × 3 box at (100, −50, 7): the reference point keeps the answer exact there too.
  const Eigen::Vector3d lo(100, -50, 7), size(1, 2, 3);
  const MassProperties m = mass_properties(test::box(lo, lo + size));
  expect_rel(m.volume, 6.0);
  for (int d = 0; d < 3; ++d) expect_rel(m.centroid(d), lo(d) + size(d) / 2);
  // I_xx = V (b² + c²) / 12 and cyclic.
  expect_rel(m.inertia(0, 0), 6.0 * (4 + 9) / 12);
  expect_rel(m.inertia(1, 1), 6.0 * (1 + 9) / 12);
  expect_rel(m.inertia(2, 2), 6.0 * (1 + 4) / 12);
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j) EXPECT_NEAR(m.inertia(i, j), 0.0, kExact * 6.5);
  expect_rel(m.principal_moments(0), 2.5);
  expect_rel(m.principal_moments(1), 5.0);
  expect_rel(m.principal_moments(2), 6.5);
  EXPECT_NEAR(std::abs(m.principal_axes(2, 0)), 1.0, kExact);  // long axis along z
  // Inertia-equivalent ellipsoid of a box: a_k = L_k √(5/12), so b/a = 2/3 and c/b = 1/2.
  expect_rel(m.ellipsoid_semi_axes(0), 3.0 * std::sqrt(5.0 / 12.0));
  expect_rel(m.elongation, 2.0 / 3.0);
  expect_rel(m.flatness, 0.5);
  expect_rel(m.extents(0), 3.0);
  expect_rel(m.extents(2), 1.0);
}

SurfaceMesh oriented(SurfaceMesh m) {
  for (Eigen::Index i = 0; i < m.faces.cols(); ++i) {
    const Eigen::Vector3d a = m.vertices.col(m.faces(0, i)), b = m.vertices.col(m.faces(1, i)),
                          c = m.vertices.col(m.faces(2, i));
    if (a.dot((b - a).cross(c - a)) < 0)
      std::swap(m.faces(1, i), m.faces(2, i));  // centred at 0: outward
  }
  return m;
}

TEST(MassProperties, RegularTetrahedron) {
  SurfaceMesh t;
  t.vertices.resize(3, 4);
  t.vertices << 1, 1, -1, -1, 1, -1, 1, -1, 1, -1, -1, 1;
  t.faces.resize(3, 4);
  t.faces << 0, 0, 0, 1, 1, 2, 3, 2, 2, 3, 1, 3;
  const MassProperties m = mass_properties(oriented(t));
  const double a = 2 * std::sqrt(2.0);  // edge
  // V = a³ / (6√2); the inertia is isotropic, I = V a² / 20.
  expect_rel(m.volume, a * a * a / (6 * std::sqrt(2.0)));
  EXPECT_NEAR(m.centroid.norm(), 0.0, kExact);
  for (int d = 0; d < 3; ++d) expect_rel(m.inertia(d, d), m.volume * a * a / 20);
  EXPECT_NEAR(m.inertia(0, 1), 0.0, kExact);
}

TEST(MassProperties, RegularOctahedron) {
  SurfaceMesh o;
  o.vertices.resize(3, 6);
  o.vertices << 1, -1, 0, 0, 0, 0, 0, 0, 1, -1, 0, 0, 0, 0, 0, 0, 1, -1;
  o.faces.resize(3, 8);
  int k = 0;
  for (int x : {0, 1})
    for (int y : {2, 3})
      for (int z : {4, 5}) o.faces.col(k++) = Eigen::Vector3i(x, y, z);
  const MassProperties m = mass_properties(oriented(o));
  // Vertices at distance 1: V = 4/3, edge a = √2, isotropic I = V a² / 10.
  expect_rel(m.volume, 4.0 / 3.0);
  for (int d = 0; d < 3; ++d) expect_rel(m.inertia(d, d), 4.0 / 3.0 * 2.0 / 10.0);
}

TEST(MassProperties, IcosphereVolumeConvergesAtSecondOrder) {
  // An inscribed polyhedron misses a cap of height ~h²/(8R) under each face: error O(n⁻²).
  const double exact = 4.0 / 3.0 * std::numbers::pi;
  double previous = 0, order = 0;
  for (int n : {4, 8, 16, 32}) {
    const double err = exact - mass_properties(geodesic_sphere(n)).volume;
    EXPECT_GT(err, 0.0);  // inscribed: always below the sphere's volume
    if (previous > 0) {
      order = std::log2(previous / err);
      std::printf("n = %2d: volume error %.3e, observed order %.4f\n", n, err, order);
    }
    previous = err;
  }
  // The asymptotic regime is reached by n = 16 → 32; a first-order method would give 1.
  EXPECT_NEAR(order, 2.0, 0.02);
}

TEST(ShapeMetrics, CubeAsperityIsTheCornerAboveItsEllipsoid) {
  // Unit cube: inertia ellipsoid radius √(5/12) (a sphere), corners at √3/2 from the centroid.
  const SurfaceMesh cube = test::unit_cube();
  const MassProperties m = mass_properties(cube);
  expect_rel(max_asperity_height(cube, m), std::sqrt(3.0) / 2 - std::sqrt(5.0 / 12.0));
  expect_rel(max_asperity_rel(cube, m), (std::sqrt(3.0) / 2 - std::sqrt(5.0 / 12.0)) /
                                            std::cbrt(3.0 / (4.0 * std::numbers::pi)));
}

TEST(ShapeMetrics, SphereHasNoAsperityAndIdenticalMeshesNoChange) {
  const SurfaceMesh s = geodesic_sphere(16);
  const MassProperties m = mass_properties(s);
  // Vertices on the unit sphere, the equivalent ellipsoid a sphere of radius 1 − O(n⁻²):
  // at n = 16 that is below 1 % of the radius.
  EXPECT_LT(std::abs(max_asperity_rel(s, m)), 1e-2);
  const ShapeChange c = shape_change(s, m, s, m);
  EXPECT_EQ(c.volume_change_rel, 0.0);
  EXPECT_EQ(c.centroid_shift_rel, 0.0);
  EXPECT_EQ(c.max_asperity_change_rel, 0.0);
}

}  // namespace
}  // namespace asperity::geometry
