// Whole collisions in the FEM/DEM world: conservation, symmetry, elastic rebound, rigid limit,
// inverted elements.
#include <gtest/gtest.h>

#include "scenes/fdem_scenes.hpp"

namespace asperity::fdem {
namespace {

using scenes::run_impact;

// Two identical balls, the second the mirror image of the first through x = 0, head-on at
// ±1 m/s. Internal and contact forces are equal and opposite pair by pair, so the total momentum
// (zero) is conserved to round-off: 1e-12 of one ball's momentum. Mirror symmetry: every node of
// the second ball stays the mirror of its twin, to 1e-9 of the radius (only the summation order
// differs between the two, so round-off is all that may differ).
TEST(Collisions, HeadOnIdenticalBallsConserveMomentumAndMirror) {
  const double r = 0.1, v = 1.0;
  const Material m = scenes::rubbery();
  const TetMesh left = scenes::translated(ball_mesh(r, 3), Vec3(-r - 0.002, 0, 0));
  WorldDef def;
  def.bodies.push_back({.name = "left",
                        .kind = BodyKind::deformable,
                        .mesh = left,
                        .material = m,
                        .velocity = Vec3(v, 0, 0)});
  def.bodies.push_back({.name = "right",
                        .kind = BodyKind::deformable,
                        .mesh = scenes::mirrored_x(left),
                        .material = m,
                        .velocity = Vec3(-v, 0, 0)});
  World w = make_world(def);
  const double p_ball = w.bodies[0].mass * v;
  const scenes::Impact im = run_impact(w, 0.1);
  ASSERT_TRUE(w.failure.empty()) << w.failure;
  ASSERT_GT(im.peak_force, 0);
  EXPECT_LT(momentum(w).norm(), 1e-12 * p_ball);
  const int n = w.bodies[0].node_end;
  double asym = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3 twin = w.x.col(n + i);
    asym = std::max(asym, (w.x.col(i) - Vec3(-twin.x(), twin.y(), twin.z())).norm());
  }
  EXPECT_LT(asym, 1e-9 * r);
  // They bounced: each ball now moves away from the other.
  EXPECT_LT(body_velocity(w, 0).x(), 0);
}

// An elastic ball on a fixed block at low speed: the potential contact is conservative and the
// integrator symplectic, so the energy error stays small (< 2 %, the gate), and little
// energy stays in vibration (restitution > 0.9).
TEST(Collisions, ElasticImpactConservesEnergyAndRebounds) {
  const double r = 0.1, v = 1.0;
  World w =
      make_world(scenes::ball_on_block(r, 4, v, BodyKind::deformable, scenes::rubbery(), 0.002));
  const scenes::Impact im = run_impact(w, 0.1);
  ASSERT_TRUE(w.failure.empty()) << w.failure;
  ASSERT_GT(im.peak_force, 0);
  EXPECT_LT(im.drift, 0.02);
  const double e = -im.v_after.z() / im.v_before.z();
  EXPECT_GT(e, 0.9) << "restitution " << e;
  EXPECT_LE(e, 1.0 + 1e-3);
}

// A rigid polyhedron and the same mesh deformable but 1000× stiffer than the penalty: the
// contact compliance is then the penalty's alone in both, so the peak forces agree within a few
// per cent (3 %: the deformable ball's own compliance is ~1e-3 of the penalty's plus its
// vibration).
TEST(Collisions, RigidPolyhedronMatchesVeryStiffDeformable) {
  const double r = 0.1, v = 0.5;
  Material stiff = scenes::rubbery();
  stiff.young = 1e11;
  WorldDef rigid_def = scenes::ball_on_block(r, 3, v, BodyKind::rigid, stiff, 0.001);
  WorldDef soft_def = scenes::ball_on_block(r, 3, v, BodyKind::deformable, stiff, 0.001);
  rigid_def.contact.penalty = soft_def.contact.penalty = 1e8;
  World rigid = make_world(rigid_def), deformable = make_world(soft_def);
  const scenes::Impact a = run_impact(rigid, 0.1), b = run_impact(deformable, 0.1);
  ASSERT_TRUE(deformable.failure.empty()) << deformable.failure;
  ASSERT_GT(a.peak_force, 0);
  EXPECT_NEAR(b.peak_force / a.peak_force, 1.0, 0.03)
      << "rigid " << a.peak_force << " N, deformable " << b.peak_force << " N";
  EXPECT_NEAR(b.duration / a.duration, 1.0, 0.03);
}

// A step far above the critical one makes elements invert; the world names body, element and
// time and stops.
TEST(Collisions, InvertedElementIsDetectedAndNamed) {
  World w = make_world(
      scenes::ball_on_block(0.1, 3, 20.0, BodyKind::deformable, scenes::rubbery(), 0.0005));
  const double dt = 20 * critical_step(w).critical;
  for (int k = 0; k < 2000 && w.failure.empty(); ++k) step(w, dt);
  ASSERT_FALSE(w.failure.empty());
  EXPECT_NE(w.failure.find("body \"ball\" element "), std::string::npos) << w.failure;
  EXPECT_NE(w.failure.find("inverted"), std::string::npos) << w.failure;
  EXPECT_NE(w.failure.find(" at t = "), std::string::npos) << w.failure;
  const long steps = w.steps;
  step(w, dt);
  EXPECT_EQ(w.steps, steps);  // stopped
}

}  // namespace
}  // namespace asperity::fdem
