// The scene's derived contact constants (solver/scene/resolve.hpp), held against their formulas:
// every world and peer adapter reads them there, so a wrong rule here is wrong everywhere.
#include <cmath>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

#include "solver/contact/restitution_damping.hpp"
#include "solver/scene/resolve.hpp"

using namespace asperity;

namespace {

// Glass and steel as a scene's materials would give them.
const Material kGlass{.name = "glass",
                      .density = 2500,
                      .young = 6.3e10,
                      .poisson = 0.23,
                      .friction = 0.3,
                      .restitution = 0.9};
Material steel() {
  Material m = kGlass;
  m.name = "steel", m.density = 7800, m.young = 2.1e11, m.poisson = 0.3;
  m.friction = 0.2, m.restitution = 0.8;
  return m;
}

}  // namespace

// k_t = 2/7 k_n unless given: the ratio at which a solid sphere's tangential and normal periods
// agree (Schäfer, Dippel & Wolf 1996). Exact in floating point: one product.
TEST(Resolve, LinearTangentialStiffnessDefaultsToTwoSeventhsOfNormal) {
  scene::ContactDef c{.law = scene::ContactLaw::linear, .kn = 7e5};
  EXPECT_DOUBLE_EQ(scene::linear_kt(c), 2e5);
  c.kt = 3e5;
  EXPECT_EQ(scene::linear_kt(c), 3e5);
}

// E* and G* from Johnson's eq. 4.22 and Mindlin's 1/G* by hand; friction and restitution the
// smaller of the two materials' unless the contact block overrides them; ζ the damping that the
// law's own map (contact/restitution_damping.hpp) gives for that restitution.
TEST(Resolve, PairConstantsFollowTheMaterialsAndTheContactBlock) {
  const Material a = kGlass, b = steel();
  scene::ContactDef c{.law = scene::ContactLaw::hertz_mindlin};
  const scene::PairConstants p = scene::pair_constants(c, a, b);
  const double e_star = 1 / ((1 - 0.23 * 0.23) / 6.3e10 + (1 - 0.3 * 0.3) / 2.1e11);
  const double g_a = 6.3e10 / (2 * 1.23), g_b = 2.1e11 / (2 * 1.3);
  const double g_star = 1 / ((2 - 0.23) / g_a + (2 - 0.3) / g_b);
  // Relative 1e-15: the same formula written with the operands in another order.
  EXPECT_NEAR(p.young_eff / e_star, 1, 1e-15);
  EXPECT_NEAR(p.shear_eff / g_star, 1, 1e-15);
  EXPECT_EQ(p.friction, 0.2);
  EXPECT_EQ(p.restitution, 0.8);
  EXPECT_EQ(p.zeta, contact::damping_for_restitution(contact::NormalLaw::hertz, 0.8));
  EXPECT_GT(p.zeta, 0);

  c = {.law = scene::ContactLaw::linear, .kn = 1e5, .friction = 0.5, .restitution = 0.5};
  const scene::PairConstants q = scene::pair_constants(c, a, b);
  EXPECT_EQ(q.friction, 0.5);
  EXPECT_EQ(q.restitution, 0.5);
  EXPECT_EQ(q.zeta, contact::damping_for_restitution(contact::NormalLaw::linear, 0.5));
  // Elastic pair: no damping.
  c.restitution = 1.0;
  EXPECT_EQ(scene::pair_constants(c, a, b).zeta, 0);
}

// m* = m1 m2 / (m1 + m2): two equal masses give half of one; a fixed body (infinite mass) leaves
// the other's own, whichever side it is on.
TEST(Resolve, EffectiveMassOfAPairAndAgainstAFixedBody) {
  EXPECT_DOUBLE_EQ(effective_mass(2.0, 2.0), 1.0);
  EXPECT_DOUBLE_EQ(effective_mass(1.0, 3.0), 0.75);
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(effective_mass(0.3, inf), 0.3);
  EXPECT_EQ(effective_mass(inf, 0.3), 0.3);
}

// A sphere's mass is ρ 4/3 π r³.
TEST(Resolve, SphereMass) {
  scene::SceneDef s;
  s.materials = {kGlass};
  s.bodies.push_back({.name = "ball", .material = 0, .shape = scene::SphereShape{.radius = 0.01}});
  EXPECT_NEAR(scene::sphere_mass(s, 0) / (2500 * 4.0 / 3.0 * std::numbers::pi * 1e-6), 1, 1e-15);
}
