// The refined sphere of the Hertz scenes and the study's sphere test (geometry/refined_sphere.hpp):
// on the sphere, fine where asked, and its chord error falling at second order in the edge.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "solver/geometry/geodesic_sphere.hpp"
#include "solver/geometry/refined_sphere.hpp"

namespace asperity::geometry {
namespace {

constexpr double kR = 0.025;

// The largest depth below the sphere of a facet centroid within `patch` of `focus`: the chord
// error a contact there sees.
double max_centroid_depth(const SurfaceMesh& s, const Vec3& focus, double patch) {
  double depth = 0;
  for (Eigen::Index f = 0; f < s.faces.cols(); ++f) {
    const Vec3 c = (s.vertices.col(s.faces(0, f)) + s.vertices.col(s.faces(1, f)) +
                    s.vertices.col(s.faces(2, f))) /
                   3.0;
    if ((c - focus).norm() <= patch) depth = std::max(depth, kR - c.norm());
  }
  return depth;
}

TEST(RefinedSphere, VerticesOnTheSphereAndEdgesFineInThePatch) {
  const double edge = 0.0167 * kR, patch = 0.15 * kR;
  const Vec3 focus(0, 0, -kR);
  const SurfaceMesh s = refined_sphere(8, kR, edge, patch, focus);
  for (Eigen::Index i = 0; i < s.vertices.cols(); ++i)
    ASSERT_NEAR(s.vertices.col(i).norm(), kR, 1e-14);  // projected: round-off of the division
  // Every edge whose midpoint lies in the patch meets the size (the bisection's stopping rule,
  // after the last pass, which moved nothing); 1e-12: the projection's round-off.
  int inside = 0;
  for (Eigen::Index f = 0; f < s.faces.cols(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = s.vertices.col(s.faces(k, f)), b = s.vertices.col(s.faces((k + 1) % 3, f));
      if ((0.5 * (a + b) - focus).norm() > patch) continue;
      ++inside;
      EXPECT_LE((a - b).norm(), edge * (1 + 1e-12));
    }
  }
  // The patch's area over an equilateral facet's: about 2π(0.15R)²/(√3/4 e²) ≈ 1100 facets.
  EXPECT_GT(inside, 1000);
}

TEST(RefinedSphere, ChordErrorFallsAtSecondOrder) {
  // A facet of edge e on a sphere of radius R sits at most about e²/(6R) below it (an
  // equilateral one's centroid); halving e divides the depth by 4.
  const double patch = 0.15 * kR;
  const Vec3 focus(0, 0, -kR);
  double prev = 0;
  for (double edge : {0.04 * kR, 0.02 * kR, 0.01 * kR}) {
    const double d = max_centroid_depth(refined_sphere(8, kR, edge, patch, focus), focus, patch);
    EXPECT_LT(d, edge * edge / (6 * kR) * 1.5);  // bisected facets are not equilateral: 1.5
    if (prev > 0) {
      const double order = std::log2(prev / d);
      EXPECT_NEAR(order, 2.0, 0.3);
    }
    prev = d;
  }
}

TEST(RefinedSphere, TheIcosphereLowestVertexIsTheSouthPole) {
  // Frequency 8 is even, and the z axis passes through the midpoints of two of the icosahedron's
  // edges ((0, ±1, −φ)), so the lowest vertex is the pole: the Hertz scenes' focus (0, 0, −R) and
  // the study's (the lowest vertex) are the same point, to the last bit (so both builders that
  // refined_sphere replaced made the same mesh from the same arguments).
  SurfaceMesh ico = geodesic_sphere(8);
  ico.vertices *= kR;
  const Vec3 low = lowest_vertex(ico);
  EXPECT_EQ(low.x(), 0.0);
  EXPECT_EQ(low.y(), 0.0);
  EXPECT_EQ(low.z(), -kR);
}

}  // namespace
}  // namespace asperity::geometry
