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
//
// The peak is gated after the T/20 moving average (docs/physics.md, FEM/DEM point 4), as the
// pair's is: since the lifting of flat surface tetrahedra is ranked by the element step (wt-step,
// this round), the coarsest level's mesh differs (14 573 tetrahedra instead of 14 375) and its raw
// peak moved from +7.38 to +7.04 % while the filtered one stayed at +6.66 %: three raw peaks
// +7.04, +6.46, +5.86 % fall by equal steps, so Richardson reads them as order −0.08 with a limit
// of +27 %, which is the ringing, not the contact. Filtered: +6.66, +5.63, +5.19 %, order 2.47,
// the finest level 0.32 % from the limit +4.87 %, against the finite sphere's +5.28 %. The raw
// finest peak is still held within 2 % of the finite sphere (+5.86 against +5.28 %), so the
// ringing the filter removes stays bounded.
TEST(HertzConvergence, WholeFieldRefinementConverges) {
  const Sequence q = sequence(Setup::block, hertz::kSpeed, {2.0, kRatio, 1.0});
  expect_converges(q, "block a/R 0.107", /*filtered=*/true);
  expect_matches_finite_sphere(q, "block a/R 0.107", /*filtered=*/true);
  EXPECT_NEAR(q.levels.back().err_force, hertz::finite_sphere(q).peak, 0.02)
      << "raw peak of the finest level against the finite sphere";
}

}  // namespace
}  // namespace asperity::fdem
