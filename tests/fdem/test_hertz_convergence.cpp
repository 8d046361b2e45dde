// Hertz by element size (issue 11): a deformable sphere whose geometry stays fixed (a faceted
// sphere fine at its strike point, scenes/hertz_spheres.hpp) is meshed with a size field
// graded towards the contact and refined as a whole, and strikes a fixed block; the peak force
// and contact duration are compared with Hertz's impact. The table it prints is
// reports/fem/hertz_convergence.md.
#include <gtest/gtest.h>

#include <vector>

#include "tests/fdem/hertz_gate.hpp"

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
//
// A fourth level (s = 1/√2, 179 533 tetrahedra, 244 s of run CPU: bench_hertz, this round) keeps
// falling: filtered +4.68 %, duration −3.48 %, below this gate's extrapolated limit and 0.60 point
// below the finite sphere in peak. So the three levels are not asymptotic, and the limit's
// agreement with the finite sphere is a statement about them (reports/fem/hertz_convergence.md).
//
// "The finite sphere" is now the dynamic reference (hertz_gate.hpp; reports/fem/
// finite_sphere_dynamic.md): +5.10 % step-mean peak, +4.92 % filtered, −3.31 % duration at the
// nominal mass, against the quasi-static +5.27 / +5.08 / −3.71 % (printed beside it). The fourth
// level's filtered +4.68 % is 0.24 point below it.
//
// The small-strain linear law (the reference's material) on the same four levels is 0.24, 0.36,
// 0.42, 0.48 point stiffer in filtered peak (+5.16 % at s = 1/√2: 0.23 point above the dynamic
// reference, 0.08 above the quasi-static) and falls by the same decrements (0.91, 0.38, 0.45); a
// fifth linear level (s = 1/2) falls by only 0.10 to +5.06 %. At a/R = 0.15 the fifth linear
// level (457 870 tetrahedra, 708 s of run CPU) settles the filtered peak onto the dynamic reference
// (+6.16 against +6.15 %) while its duration still moves (−4.84 %, 0.35 point from the fourth);
// this gate keeps the neo-Hookean law (reports/fem/hertz_convergence.md, last sections).
TEST(HertzConvergence, WholeFieldRefinementConverges) {
  const Sequence q = sequence(Setup::block, hertz::kSpeed, {2.0, kRatio, 1.0});
  expect_converges(q, "block a/R 0.107", /*filtered=*/true);
  expect_matches_finite_sphere(q, "block a/R 0.107", /*filtered=*/true);
  EXPECT_NEAR(q.levels.back().err_force, hertz::finite_sphere(q).peak, 0.02)
      << "raw peak of the finest level against the finite sphere";
}

// The same at a/R = 0.15 (block speed 0.465 m/s, the contact zone's elements and facets scaled
// by 1.40 with the contact radius: hertz_series.hpp). Label `slow`: 111 s of run CPU and 21 s of
// meshing (132 s; one run each on the loaded machine, bench_hertz). Measured at s = 2, √2, 1
// (reports/fem/hertz_convergence.md): T/20-filtered peak +7.49, +6.47, +5.94 % (raw +7.99, +7.11,
// +6.79 %), duration −7.16, −6.12, −5.37 %; observed order 1.92 (filtered peak) and 0.91
// (duration); the finite sphere at the sequence's mass is +7.69 / −5.31 %, so the finest level
// is 1.75 points (filtered), 0.90 (raw) and 0.06 (duration) from it.
//
// What is gated, and what is not: the sequence converges (errors falling at every level, order >
// 0.75, impulse 2mv), and its finest level is within the 2 % of the finite sphere in
// filtered peak, raw peak and duration. Not gated: the Richardson limit. The duration's order is
// below 1 (its extrapolation multiplies the last step by 2.7 and puts the finest level 2.04 % from
// a limit of −3.43 %), and a fourth level says why: at s = 1/√2 (bench_hertz, 168 325
// tetrahedra, 187 s of run CPU) the errors keep falling at order 0.5–0.7 (filtered peak +5.49 %,
// raw +6.32 %, duration −4.77 %), past the finite sphere in duration and 2.20 points below it in
// filtered peak. So at a/R = 0.15 the levels are not yet asymptotic, and agreement with the finite
// sphere beyond s = 1 is not established; neither the penalty (α = 30: filtered peak and
// duration within 0.07 point, HertzPenalty), the step (0.25 instead of 0.5 of the critical step:
// within 0.02 point) nor the contact zone's resolution (the a/R = 0.107 zone, a/h 3.8 instead of
// 2.7: filtered peak within 0.04 point at s = 1) is what moves it. Against the dynamic reference
// (hertz_gate.hpp: +6.31 % step-mean, +6.25 % filtered, −4.74 % duration at the nominal mass;
// the quasi-static +7.71 / +7.52 / −5.32 % printed beside it) the fourth level is 0.76 point
// below in filtered peak and 0.03 in duration.
TEST(HertzConvergence, LargerContactConverges) {
  const Sequence q =
      sequence(Setup::block, hertz::speed_for(0.15, scenes::rubbery()), {2.0, kRatio, 1.0});
  const std::vector<hertz::Level>& l = q.levels;
  for (std::size_t i = 1; i < l.size(); ++i)
    EXPECT_LT(l[i].err_force, l[i - 1].err_force) << "raw peak, level " << i;
  expect_converges(q, "block a/R 0.15", /*filtered=*/true, /*own_error=*/false);
  hertz::expect_finest_matches_finite_sphere(q, "block a/R 0.15");
}

}  // namespace
}  // namespace asperity::fdem
