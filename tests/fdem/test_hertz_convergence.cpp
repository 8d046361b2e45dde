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
// 1.1 % (peak) and 0.5 % (duration) from the extrapolated limit. The limit is stiffer than Hertz
// by +4.8 % in peak (−3.6 % duration) at a/R = 0.107: Hertz's theory is that of half-spaces,
// and the finite sphere (validation/reference/finite_sphere.hpp, an independent axisymmetric
// solution) is +5.3 % / −3.7 % from Hertz there; the 3D limit is within 0.5 point of it
// (docs/physics.md, FEM/DEM points 5–7). So the 2 % is held against the finite sphere.
TEST(HertzConvergence, WholeFieldRefinementConverges) {
  const Sequence q = sequence(Setup::block, hertz::kSpeed, {2.0, kRatio, 1.0});
  expect_converges(q, "block a/R 0.107");
  expect_matches_finite_sphere(q, "block a/R 0.107");
}

// The same at a/R = 0.15 (block speed 0.465 m/s, the contact zone's elements and facets scaled
// by 1.40 with the contact radius: hertz_series.hpp), the second contact size of the finite-
// sphere comparison. Label `slow`: 98 s of run CPU on the loaded machine. Measured at s = 2, √2,
// 1: peak +8.0, +7.1, +6.6 %, duration −7.2, −6.1, −5.4 %; order 1.8 / 1.2, the finest level
// 0.6 / 1.3 % from the limit, which is +6.1 / −4.1 % from Hertz against the finite sphere's
// +7.7 / −5.3 %: 1.6 / 1.2 points apart, the largest gap of the a/R series (its levels are not
// yet asymptotic: refining the contact zone alone raises the peak, reports/fem/
// hertz_convergence.md).
TEST(HertzConvergence, LargerContactConverges) {
  const Sequence q =
      sequence(Setup::block, hertz::speed_for(0.15, scenes::rubbery()), {2.0, kRatio, 1.0});
  expect_converges(q, "block a/R 0.15");
  expect_matches_finite_sphere(q, "block a/R 0.15");
}

}  // namespace
}  // namespace asperity::fdem
