// The volume laws on rigid polyhedra (contact/overlap_volume.hpp, contact/volume_hertz.hpp,
// contact/volume_linear.hpp): exact overlap geometry, the force–approach exponents of a cube's
// vertex, edge and face, and elastic impacts that conserve energy and momentum.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "scenes/volume_scenes.hpp"
#include "solver/contact/overlap_volume.hpp"
#include "solver/contact/volume_linear.hpp"

namespace asperity::fdem {
namespace {

namespace vs = volume_scenes;

// Every surface triangle of `a` clipped by every tetrahedron of `b`.
contact::OverlapSide side_of(const TetMesh& a, const TetMesh& b, const Vec3& origin) {
  contact::OverlapSide s;
  for (Eigen::Index f = 0; f < a.surface.cols(); ++f) {
    const contact::Triangle tri{a.nodes.col(a.surface(0, f)), a.nodes.col(a.surface(1, f)),
                                a.nodes.col(a.surface(2, f))};
    for (Eigen::Index t = 0; t < b.tets.cols(); ++t) {
      contact::clip_triangle_in_tet(tri,
                                    {b.nodes.col(b.tets(0, t)), b.nodes.col(b.tets(1, t)),
                                     b.nodes.col(b.tets(2, t)), b.nodes.col(b.tets(3, t))},
                                    origin, s);
    }
  }
  return s;
}

// Two unit cubes offset by (0.3, 0.2, 0.1): the overlap is the box 0.7 × 0.8 × 0.9 (V = 0.504)
// centred at (0.15, 0.1, 0.05), and translating A by dx along an axis changes V by the overlap's
// face normal to it: S_A = (0.72, 0.63, 0.56). Exact geometry, so round-off only (1e-12).
TEST(OverlapVolume, TwoBoxesExactly) {
  const TetMesh a = vs::cube(1.0, Mat3::Identity(), Vec3::Zero());
  const TetMesh b = vs::cube(1.0, Mat3::Identity(), Vec3(0.3, 0.2, 0.1));
  const Vec3 origin(0.01, -0.02, 0.03);
  const contact::OverlapSide sa = side_of(a, b, origin), sb = side_of(b, a, origin);
  const contact::Overlap o = contact::combine(sa, sb, origin);
  EXPECT_NEAR(o.volume, 0.7 * 0.8 * 0.9, 1e-12);
  EXPECT_LT((o.centroid - Vec3(0.15, 0.1, 0.05)).norm(), 1e-12);
  EXPECT_LT((o.area - Vec3(0.72, 0.63, 0.56)).norm(), 1e-12);
  EXPECT_LT((sa.area + sb.area).norm(), 1e-12);
  // Total moment about any point vanishes (∮ (x − o) × n dS = 0): no spurious torque.
  EXPECT_LT((sa.moment + sb.moment).norm(), 1e-12);
}

// A faceted sphere pressed δ = 0.1 R into a plane (a block's top): its cap volume tends to the
// sphere's π δ² (R − δ/3) as the facets shrink, with the chord error O(n⁻²) (geodesic frequency
// n; measured 0.226, 0.060, 0.0154 at n = 4, 8, 16: ratios 3.8 and 3.9). Asserted: each doubling
// divides the error by more than 3.5 (order > 1.8) and n = 16 is within 2 %.
TEST(OverlapVolume, FacetedSphereCapConverges) {
  const double r = 1.0, d = 0.1;
  const double exact = std::numbers::pi * d * d * (r - d / 3);
  const TetMesh block = vs::block(r, vs::stone()).mesh;
  double prev = 0;
  for (const int n : {4, 8, 16}) {
    const TetMesh s = vs::faceted_sphere(r, n, Vec3(0, 0, r - d));
    const Vec3 o(0, 0, 0);
    const contact::Overlap ov = contact::combine(side_of(s, block, o), side_of(block, s, o), o);
    const double err = std::abs(ov.volume / exact - 1);
    std::printf("n = %d: cap volume error %.3e\n", n, err);
    if (n > 4) {
      EXPECT_LT(err, prev / 3.5) << "n = " << n;
    }
    prev = err;
  }
  EXPECT_LT(prev, 0.02);
}

// Force on a cube pressed δ into a fixed block, from the world's first force evaluation.
double cube_force(const Mat3& rot, double depth, ContactLaw law) {
  const double a = 0.1;
  WorldDef def;
  TetMesh c = vs::cube(a, rot, Vec3::Zero());
  c.nodes.row(2).array() -= vs::lowest(c) + depth;
  def.bodies.push_back(
      {.name = "cube", .kind = BodyKind::rigid, .mesh = c, .material = vs::stone()});
  def.bodies.push_back(vs::block(a, vs::stone()));
  def.contact.law = law;
  def.contact.kv = 1e9;
  return make_world(def).contacts.force.col(0).norm();
}

// Exponent p of F ∝ δ^p from δ = 1e-4 a and 1e-3 a. The overlap of a vertex is a tetrahedron
// (V ∝ δ³), of an edge a prism (V ∝ δ²), of a face a slab (V ∝ δ), exactly while δ is below the
// next vertex, so the exponent is exact up to round-off (1e-6). volume-hertz: F = (5/4) c V^{1/4}
// dV/dδ gives 11/4, 3/2, 1/4; volume-linear F = k_v V gives 3, 2, 1 (docs/physics.md).
double exponent(const Mat3& rot, ContactLaw law) {
  const double a = 0.1, d1 = 1e-4 * a, d2 = 1e-3 * a;
  return std::log(cube_force(rot, d2, law) / cube_force(rot, d1, law)) / std::log(d2 / d1);
}

TEST(VolumeLaws, CubeVertexEdgeFaceExponents) {
  EXPECT_NEAR(exponent(vs::vertex_down(), ContactLaw::volume_hertz), 2.75, 1e-6);
  EXPECT_NEAR(exponent(vs::edge_down(), ContactLaw::volume_hertz), 1.5, 1e-6);
  EXPECT_NEAR(exponent(Mat3::Identity(), ContactLaw::volume_hertz), 0.25, 1e-6);
  EXPECT_NEAR(exponent(vs::vertex_down(), ContactLaw::volume_linear), 3.0, 1e-6);
  EXPECT_NEAR(exponent(vs::edge_down(), ContactLaw::volume_linear), 2.0, 1e-6);
  EXPECT_NEAR(exponent(Mat3::Identity(), ContactLaw::volume_linear), 1.0, 1e-6);
}

// volume-linear on a face: F = k_v V = k_v a² δ exactly (1e-9: round-off of the clipping).
TEST(VolumeLaws, LinearFaceForceIsKvTimesVolume) {
  const double a = 0.1, d = 1e-4;
  EXPECT_NEAR(cube_force(Mat3::Identity(), d, ContactLaw::volume_linear), 1e9 * a * a * d,
              1e-9 * 1e9 * a * a * d);
}

// A cube dropped on its vertex, edge or face onto a fixed block under volume-hertz at the
// default step (0.01 of the predicted one): the law is a potential, so the rebound is elastic
// (restitution 1 ± 1e-3, the gate) and the energy is kept (drift < 1e-3). Each drop is
// symmetric about the vertical, so the rebound stays vertical.
TEST(VolumeLaws, CubeDropsAreElastic) {
  const double a = 0.1, v = 0.5;
  for (const Mat3& rot : {vs::vertex_down(), vs::edge_down(), Mat3(Mat3::Identity())}) {
    WorldDef def;
    TetMesh c = vs::cube(a, rot, Vec3::Zero());
    c.nodes.row(2).array() += 1e-4 - vs::lowest(c);
    def.bodies.push_back({.name = "cube",
                          .kind = BodyKind::rigid,
                          .mesh = c,
                          .material = vs::stone(),
                          .velocity = Vec3(0, 0, -v)});
    def.bodies.push_back(vs::block(a, vs::stone()));
    def.contact.law = ContactLaw::volume_hertz;
    World w = make_world(def);
    const vs::Impact im = vs::run_impact(w, 1.0);
    ASSERT_GT(im.peak_force, 0);
    EXPECT_NEAR(-im.v_after.z() / im.v_before.z(), 1.0, 1e-3);
    EXPECT_LT(im.drift, 1e-3);
    EXPECT_LT(std::hypot(im.v_after.x(), im.v_after.y()), 1e-6 * v);
  }
}

// Two free cubes, one tumbling, strike off-centre: the forces and torques of the pair are the
// gradient of one energy W(V), equal and opposite with torques that sum to zero about any point,
// so linear and angular momentum are kept to round-off (1e-9 relative; a cube's inertia is
// isotropic, so free rotation adds no integrator error) and the energy within 1e-3.
TEST(VolumeLaws, TumblingCubesConserveMomentumAndEnergy) {
  const double a = 0.1;
  WorldDef def;
  def.bodies.push_back({.name = "left",
                        .kind = BodyKind::rigid,
                        .mesh = vs::cube(a, vs::edge_down(), Vec3(-0.8 * a - 0.002, 0.02, 0)),
                        .material = vs::stone(),
                        .velocity = Vec3(0.5, 0, 0.05),
                        .angular_velocity = Vec3(1, 3, 2)});
  def.bodies.push_back({.name = "right",
                        .kind = BodyKind::rigid,
                        .mesh = vs::cube(a, vs::vertex_down(), Vec3(0.8 * a, 0, 0)),
                        .material = vs::stone(),
                        .velocity = Vec3(-0.5, 0, 0)});
  def.contact.law = ContactLaw::volume_hertz;
  World w = make_world(def);
  auto angular = [&] {
    Vec3 l = Vec3::Zero();
    for (const RigidBody& rb : w.rigid) {
      const Mat3 r = rb.orientation.toRotationMatrix();
      l += rb.centre.cross(rb.mass * rb.velocity) + r * rb.inertia_body * r.transpose() * rb.omega;
    }
    return l;
  };
  const Vec3 p0 = momentum(w), l0 = angular();
  const double p_scale = w.rigid[0].mass * 0.5;
  const double l_scale = p_scale * a;
  const vs::Impact im = vs::run_impact(w, 1.0);
  ASSERT_GT(im.peak_force, 0);
  EXPECT_LT((momentum(w) - p0).norm(), 1e-9 * p_scale);
  EXPECT_LT((angular() - l0).norm(), 1e-9 * l_scale);
  EXPECT_LT(im.drift, 1e-3);
}

}  // namespace
}  // namespace asperity::fdem
