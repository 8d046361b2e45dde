// Hertz by element size (issue 11): a deformable sphere whose geometry stays fixed (a faceted
// sphere fine at its strike point, tests/fdem/hertz_spheres.hpp) is meshed with a size field
// graded towards the contact and refined as a whole, and strikes a fixed block; the peak force
// and contact duration are compared with Hertz's impact. The table it prints is
// reports/fem/hertz_convergence.md.
#include <gtest/gtest.h>

#include "hertz_gate.hpp"

namespace asperity::fdem {
namespace {

using hertz::expect_converges;
using hertz::expect_matches_finite_sphere;
using hertz::kRatio;
using hertz::sequence;
using hertz::Sequence;
using hertz::Setup;

// Label `slow`: three levels, 154 s of run CPU on the loaded machine (budget 3 min).
// Measured (reports/fem/hertz_convergence.md) at s = 2, √2, 1: peak +7.4, +6.5, +5.9 %,
// duration −6.6, −4.8, −4.1 %; observed order 1.3 (peak) and 2.6 (duration), the finest level
// 1.1 % (peak) and 0.5 % (duration) from the extrapolated limit. The solver converges; the limit
// it converges to is stiffer than Hertz by +4.8 % in peak (−3.6 % duration) at a/R = 0.107, a
// deviation that grows with the contact size (a/R = 0.15 on the finest mesh: +7.4 %) and is the
// same with small-strain linear elasticity (+6.3 %, +7.8 %): the finite sphere, not the
// half-space of Hertz's theory (docs/physics.md). So this test gates the convergence (falling
// errors, order, the finest level's own error) and prints, without gating, the distance to
// Hertz; the "within 2 % of Hertz" is not met.
TEST(HertzConvergence, WholeFieldRefinementConverges) {
  const Sequence q = sequence(Setup::block, hertz::kSpeed, {2.0, kRatio, 1.0});
  expect_converges(q, "block a/R 0.107");
  expect_matches_finite_sphere(q, "block a/R 0.107");
}

// The same at a/R = 0.15 (block speed 0.465 m/s, the contact zone's elements and facets scaled
// by 1.40 with the contact radius: hertz_series.hpp), the second contact size of the finite-
// sphere comparison. Label `slow`: BLOCK015_CPU s of run CPU on the loaded machine.
// Measured: BLOCK015_FIGURES.
TEST(HertzConvergence, LargerContactConverges) {
  const Sequence q =
      sequence(Setup::block, hertz::speed_for(0.15, scenes::rubbery()), {2.0, kRatio, 1.0});
  expect_converges(q, "block a/R 0.15");
  expect_matches_finite_sphere(q, "block a/R 0.15");
}

}  // namespace
}  // namespace asperity::fdem
