// The principal radii at a surface's lowest vertex (geometry/local_curvature.hpp) on an ellipsoid,
// whose radii at its pole are known: x²/A² + y²/B² + z²/C² = 1 at (0, 0, −C) has R_x = A²/C and
// R_y = B²/C.
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "solver/geometry/geodesic_sphere.hpp"
#include "solver/geometry/local_curvature.hpp"

namespace asperity::geometry {
namespace {

// A geodesic icosphere of frequency n turned so that one vertex sits at the south pole, then
// scaled to the ellipsoid (A, B, C): every vertex lies on the ellipsoid and the pole is the
// lowest vertex.
SurfaceMesh ellipsoid(int n, double a, double b, double c) {
  SurfaceMesh s = geodesic_sphere(n);
  const Eigen::Quaterniond q =
      Eigen::Quaterniond::FromTwoVectors(Vec3(s.vertices.col(0)).normalized(), Vec3(0, 0, -1));
  for (Eigen::Index i = 0; i < s.vertices.cols(); ++i) {
    const Vec3 v = q * Vec3(s.vertices.col(i)).normalized();
    s.vertices.col(i) = Vec3(a * v.x(), b * v.y(), c * v.z());
  }
  return s;
}

TEST(LocalCurvature, EllipsoidPoleRadiiConvergeAtSecondOrder) {
  const double a = 1.0, b = 0.8, c = 0.6;
  const double rx = a * a / c, ry = b * b / c;  // 1.667 and 1.067
  double previous = 0;
  for (int n : {8, 16, 32, 64}) {
    const SurfaceMesh s = ellipsoid(n, a, b, c);
    // The patch: 2.5 mean edges (about two rings of vertices), as the study uses.
    const LocalCurvature k = lowest_point_curvature(s, 2.5 * mean_edge_length(s));
    ASSERT_TRUE(k.convex());
    EXPECT_NEAR(k.point.z(), -c, 1e-12);
    const double err = std::max(std::abs(k.radius_max / rx - 1), std::abs(k.radius_min / ry - 1));
    const double equivalent = std::abs(k.equivalent_radius() / std::sqrt(rx * ry) - 1);
    std::cout << "n " << n << ": R " << k.radius_min << ", " << k.radius_max << " (exact " << ry
              << ", " << rx << "), worst error " << err << ", equivalent radius error "
              << equivalent << ", " << k.samples << " vertices\n";
    if (previous > 0) {
      // Halving the edge: the error falls at order ≥ 1.5 (second order expected: the fit's
      // residual is the surface's quartic term over a patch that shrinks with the edge; 1.5
      // leaves room for the patch's changing vertex count).
      EXPECT_LT(err, previous / std::pow(2.0, 1.5)) << n;
    }
    previous = err;
  }
  // The finest (edge ≈ 0.02 of the smallest radius): within 0.5 %.
  EXPECT_LT(previous, 0.005);
}

TEST(LocalCurvature, SphereGivesItsRadiusAndAFlatFaceNone) {
  SurfaceMesh s = geodesic_sphere(16);
  s.vertices *= 0.3;
  const LocalCurvature k = lowest_point_curvature(s, 2.5 * mean_edge_length(s));
  // A sphere's vertices: both radii 0.3 m to the fit's second-order error at this edge (0.02 m,
  // 7 % of R: about 0.5 %).
  EXPECT_NEAR(k.radius_min / 0.3, 1.0, 0.01);
  EXPECT_NEAR(k.radius_max / 0.3, 1.0, 0.01);
  // A cube's lowest vertices are a flat face: no curvature, no Hertz sphere.
  SurfaceMesh cube;
  cube.vertices.resize(3, 8);
  for (int i = 0; i < 8; ++i) cube.vertices.col(i) = Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  cube.faces.resize(3, 0);
  const LocalCurvature f = lowest_point_curvature(cube, 0.5);
  EXPECT_EQ(f.equivalent_radius(), 0.0);
}

}  // namespace
}  // namespace asperity::geometry
