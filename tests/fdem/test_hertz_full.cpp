// The Hertz convergence gates that take too long for CI (issue 11, item 2; label `hertz-full`,
// run with `ctest --test-dir build -L hertz-full`): the head-on pair of deformable spheres, and
// the Richardson limits of the sphere on a block over a/R = 0.05–0.15, whose distance from Hertz
// must fall towards 0 as a/R → 0. Sequences: scenes/hertz_series.hpp; figures:
// reports/fem/hertz_convergence.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tests/fdem/hertz_gate.hpp"

namespace asperity::fdem {
namespace {

using hertz::expect_converges;
using hertz::expect_matches_finite_sphere;
using hertz::kRatio;
using hertz::Level;
using hertz::sequence;
using hertz::Sequence;
using hertz::Setup;

// The head-on pair against the block, the symmetric problem's two forms. Level by level they see
// the same sphere mesh: their durations and filtered peaks agree within 0.5 % (the contact layer's
// own compliance, about h/(4αa) of the approach, is a few tenths of a percent). Their limits are
// one answer, each extrapolated from its own sequence: 2 % is the tolerance.
void expect_pair_matches_block(const Sequence& pair, const Sequence& block) {
  for (std::size_t i = 0; i < pair.levels.size(); ++i) {
    EXPECT_NEAR(pair.levels[i].err_duration, block.levels[i].err_duration, 0.005) << "level " << i;
    EXPECT_NEAR(pair.levels[i].err_force_filtered, block.levels[i].err_force_filtered, 0.005)
        << "level " << i;
  }
  EXPECT_NEAR(pair.peak_filtered.limit, block.peak_filtered.limit, 0.02);
  EXPECT_NEAR(pair.duration.limit, block.duration.limit, 0.02);
}

// The head-on pair: two equal deformable spheres (the second the mirror image of the first through
// the contact plane) at relative speed 2v, a/R = 0.15, against the sphere on the fixed block at
// v. Hertz for the pair (m/2, R/2, E*/2, 2v) is the block's at v, and so is the exact answer: the
// mid-plane is a frictionless plane of symmetry. The pair's contact is deformable against
// deformable (both bodies' potentials), the block's deformable against one large rigid
// tetrahedron, so their agreement checks the contact independently. The pair's contact costs
// about 10× the block's per step (18 000 pair evaluations per step against 3 000). Run end to end
// (2026-12-02, nice 5, load 7–13): passed; run CPU 121.4, 219.5, 361.6 s at s = 2, √2, 1 (14 988,
// 27 991, 72 586 tetrahedra per sphere), the block's 9.2, 19.1, 48.9 s; 860 s of CPU for the test
// with its meshing and the reference (53 min wall at 27 % of a core).
TEST(HertzPair, HeadOnPairConvergesAndMatchesTheBlock) {
  const double speed = hertz::speed_for(0.15, scenes::rubbery());
  const Sequence pair = sequence(Setup::pair, speed, {2.0, kRatio, 1.0});
  const Sequence block = sequence(Setup::block, speed, {2.0, kRatio, 1.0});
  // The pair's raw peak rings (+10.11, +8.62, +8.83 % at s = 2, √2, 1: not falling; +7.57, +6.54,
  // +6.01 % after the T/20 moving average: order 1.96, the finest level 0.54 % from its limit
  // +5.47 %), so its peak is gated filtered, and so is the block's where the two are compared.
  // Duration −7.29, −6.18, −5.48 %: order 1.29, limit −4.22 %, the finest level 1.25 % from it.
  expect_converges(pair, "pair", true);
  // The block sequence is LargerContactConverges' (test_hertz_convergence.cpp) and is gated as
  // there: filtered, its finest level's distance from a three-level limit printed, not gated (its
  // duration is 2.04 % from that limit at order 0.91: the a/R = 0.15 levels are not asymptotic,
  // reports/fem/hertz_convergence.md). Filtered peak +7.49, +6.47, +5.94 % (order 1.92, limit
  // +5.39 %), duration −7.16, −6.12, −5.37 % (limit −3.33 %).
  expect_converges(block, "block", /*filtered=*/true, /*own_error=*/false);
  // Against the dynamic finite sphere at this mass and speed (+6.15 % filtered, +6.28 % step-mean
  // peak, −4.74 % duration; hertz_gate.hpp) the pair's duration limit is gated: −4.22 %, 0.52
  // point short. Its peak is held against the reference through the block (level by level below;
  // the block's finest level against the reference in LargerContactConverges): the pair's finest
  // filtered peak is 0.14 point below the reference and its filtered limit 0.68 below; its raw
  // finest peak, 2.55 points above the step-mean peak, is the deformable–deformable contact's
  // ringing.
  const hertz::FiniteSphere f = hertz::finite_sphere(pair);
  EXPECT_NEAR(pair.duration.limit, f.duration, 0.02);
  // Momentum: internal and contact forces are equal and opposite pair by pair, so the total
  // momentum (zero) is conserved to round-off: 1e-12 of one sphere's (measured 1.6e-16 to 6.1e-15).
  for (const Level& x : pair.levels) EXPECT_LT(x.momentum, 1e-12) << "s " << x.s;
  // Level by level: durations 0.13, 0.06, 0.11 points apart at s = 2, √2, 1, filtered peaks 0.08,
  // 0.07, 0.07. Limits: filtered +5.47 / +5.39 %, 0.08 point apart; duration −4.22 / −3.33 %, 0.89
  // apart, the block's duration extrapolated at order 0.91.
  expect_pair_matches_block(pair, block);
}

// The head-on pair at a second contact size, a/R = 0.08 (the block's series point nearest the
// issue's middle): the symmetric problem must give the block's answer at every contact size, not
// only at the one the pair was first run at. The same gates as at 0.15: the pair's filtered peak
// and duration fall with every level at an order above 0.75, momentum to round-off, the pair and
// the block level by level within 0.5 % (the contact layers' own compliances differ by a few
// tenths of a percent, as above), the two limits within 2 % of each other and the pair's within
// 2 % of the dynamic finite sphere in peak and duration. Run end to end (2026-12-02, one core of
// the shared 2-core machine at load 4–5): passed, 2 415 s of CPU (69 min wall); the pair's run
// CPU 305, 654, 1 203 s at s = 2, √2, 1 (16 547, 34 328, 80 249 tetrahedra per sphere), the
// block's 19, 58, 100 s. Pair filtered peak +6.15, +4.50, +3.85 % (order 2.70, limit +3.43 %),
// duration −6.30, −4.35, −3.73 % (order 3.30, limit −3.44 %); raw peak +6.81, +5.34, +4.58 %;
// momentum 7e-17 to 1.6e-15 of m v. The block level by level +6.03 / −6.14, +4.44 / −4.27,
// +3.81 / −3.64 % (0.04–0.16 point from the pair), limits +3.38 / −3.33 %. The dynamic finite
// sphere: +3.36 / −2.52 % (the pair's limits 0.07 and 0.92 point from it).
TEST(HertzPair, HeadOnPairMatchesTheBlockAtASmallerContact) {
  const double speed = hertz::speed_for(0.08, scenes::rubbery());
  const Sequence pair = sequence(Setup::pair, speed, {2.0, kRatio, 1.0});
  const Sequence block = sequence(Setup::block, speed, {2.0, kRatio, 1.0});
  expect_converges(pair, "pair a/R 0.08", /*filtered=*/true, /*own_error=*/false);
  expect_matches_finite_sphere(pair, "pair a/R 0.08", /*filtered=*/true);
  for (const Level& x : pair.levels) EXPECT_LT(x.momentum, 1e-12) << "s " << x.s;
  for (std::size_t i = 0; i < pair.levels.size(); ++i) {
    std::printf("  level %zu: pair %+.4f / %+.4f, block %+.4f / %+.4f (filtered peak / duration)\n",
                i, pair.levels[i].err_force_filtered, pair.levels[i].err_duration,
                block.levels[i].err_force_filtered, block.levels[i].err_duration);
  }
  expect_pair_matches_block(pair, block);
}

// "Converges to Hertz": Hertz is the law of two half-spaces, so the finite sphere's limit may
// differ from it by a term that vanishes with the contact size a/R. The Richardson limits of the
// block sequences at a/R = 0.05, 0.08, 0.107, 0.15 (s = 2, √2, 1; the contact zone's elements and
// facets scaled with a, hertz_series.hpp), fitted by a line in a/R: the intercept is the limit's
// distance from Hertz as a/R → 0, which must be within the 2 % (the slope, the
// finite-sphere coefficient, is printed), and the distance from Hertz must grow with the contact
// at every step. Each limit is held within 2 % of the dynamic finite sphere at its own mass and
// speed. Run end to end (2026-12-02, nice 5, load 7–13; 1 114 s of CPU, 58 min wall at 32 % of a
// core), filtered peak / duration, limit against the reference (points apart):
//   a/R 0.05: s = 1 +2.67 / −2.87 % (89 680 tetrahedra, 405 s of run CPU, 61 547 steps at a
//             contact-limited 4.15e-7 s); orders 1.73 / 1.51; limit +1.77 / −1.59 against +2.09 /
//             −1.55 (0.32, 0.04);
//   a/R 0.08: s = 1 +3.81 / −3.64 %; orders 2.64 / 3.17; +3.38 / −3.33 against +3.36 / −2.52
//             (0.02, 0.81);
//   a/R 0.107: s = 1 +5.19 / −4.10 %; orders 2.47 / 2.21; +4.87 / −3.48 against +4.93 / −3.32
//             (0.06, 0.16);
//   a/R 0.15: s = 1 +5.94 / −5.37 %; orders 1.92 / 0.91; +5.39 / −3.33 against +6.15 / −4.74
//             (0.76, 1.41).
// Fit: peak +0.32 ± 0.84 % + (+0.366 ± 0.081) a/R, duration −1.45 ± 1.07 % + (−0.153 ± 0.103) a/R.
// The distance's growth is asserted on the filtered peak's limits (+1.77, +3.38, +4.87, +5.39 %)
// and on the finest levels (s = 1: the same elements per contact radius at every a/R), not on the
// duration's limits: the a/R = 0.15 duration is extrapolated at order 0.91 from levels that are
// not asymptotic (a fourth level, s = 1/√2, moves that limit from −3.33 to −2.51 %;
// reports/fem/hertz_convergence.md), and it lands 0.15 point closer to Hertz than a/R = 0.107's
// −3.48 % although the reference's step between the two is 1.42 points. That comparison failed the
// first end-to-end run; the limits stay in the fit and each within 2 % of the reference. Rerun
// as it stands: passed, the same figures to the printed digits (1 057 s of CPU, 41 min wall).
TEST(HertzSeries, LimitTendsToHertzAsTheContactShrinks) {
  std::vector<double> ar, peak, duration, finest_peak, finest_duration;
  for (const double a : {0.05, 0.08, 0.107, 0.15}) {
    const double speed = a == 0.107 ? hertz::kSpeed : hertz::speed_for(a, scenes::rubbery());
    const Sequence q = sequence(Setup::block, speed, {2.0, kRatio, 1.0});
    // Filtered peaks (the raw a/R = 0.107 peaks fall by equal steps: ringing), and the finest
    // level's distance from its limit not gated: the three levels are not asymptotic at a/R = 0.107
    // and 0.15 (fourth levels, reports/fem/hertz_convergence.md; at 0.15 the duration's finest
    // level is 2.04 % from its limit).
    expect_converges(q, "block", /*filtered=*/true, /*own_error=*/false);
    expect_matches_finite_sphere(q, "block", /*filtered=*/true);
    ar.push_back(q.levels.back().a_over_r);
    peak.push_back(q.peak_filtered.limit);
    duration.push_back(q.duration.limit);
    finest_peak.push_back(q.levels.back().err_force_filtered);
    finest_duration.push_back(q.levels.back().err_duration);
  }
  for (std::size_t i = 1; i < ar.size(); ++i) {
    EXPECT_LT(std::abs(peak[i - 1]), std::abs(peak[i])) << "limit, a/R " << ar[i - 1];
    EXPECT_LT(std::abs(finest_peak[i - 1]), std::abs(finest_peak[i])) << "s = 1, a/R " << ar[i - 1];
    EXPECT_LT(std::abs(finest_duration[i - 1]), std::abs(finest_duration[i]))
        << "s = 1, a/R " << ar[i - 1];
  }
  const hertz::Line p = hertz::fit_line(ar, peak);
  const hertz::Line d = hertz::fit_line(ar, duration);
  std::printf(
      "limit − Hertz = c0 + c1 a/R: peak c0 %+.4f ± %.4f, c1 %+.3f ± %.3f; duration c0 %+.4f ± "
      "%.4f, c1 %+.3f ± %.3f\n",
      p.c0, p.se0, p.c1, p.se1, d.c0, d.se0, d.c1, d.se1);
  EXPECT_LT(std::abs(p.c0), 0.02);
  EXPECT_LT(std::abs(d.c0), 0.02);
}

// The like-for-like convergence (issue 11, item 2): the small-strain linear law (the material of
// Hertz's theory and of the reference) at a/R = 0.107 on the three finest whole-field levels,
// s = 1, 1/√2, 1/2 (75 549, 179 533, 522 049 tetrahedra), against the dynamic finite sphere
// (hertz_gate.hpp). Measured with bench_hertz (the same run_level;
// reports/fem/hertz_convergence.md, last section): filtered peak +5.61, +5.16, +5.06 %, duration
// −4.38, −3.79, −3.50 %; the decrements shrink (0.45 then 0.10 in peak, 0.59 then 0.29 in duration:
// orders 4.3 and 2.05), limits +5.03 / −3.22 % against the reference's +4.93 / −3.32 %. The coarser
// triples (s = 2 to 1/√2) are not asymptotic (orders −0.5 to 0.5): the levels settle only below 3
// mm at the contact. Gated: every error falls; the duration's order > 0.75 and the peak's > 0 (its
// order is not yet steady: 4.3 on this triple); the finest level and the limit within the 2
// % of the reference, and the limit within 0.5 point of it (measured 0.10: five times the measured
// distance, which is what the peak limit's unsteady order leaves as its uncertainty, about 0.1
// point, plus the reference's own 0.015). Run end to end on main (2026-12-02, nice 5, the machine
// mostly idle): passed in 1 749 s wall; run CPU 59.8 + 144.6 + 492.8 s (the finest level's step is
// contact-limited: 23 315 steps at 7.4e-7 s), the rest meshing and set-up; filtered peak +5.61,
// +5.16, +5.06 %, duration −4.38, −3.79, −3.50 %; orders 4.27 (filtered peak) and 2.11
// (duration); limits +5.03 / −3.24 % against the dynamic reference's +4.93 / −3.32 %.
TEST(HertzConvergence, LinearLawSettlesOntoTheDynamicReference) {
  const Sequence q =
      sequence(Setup::block, hertz::kSpeed, {1.0, 1.0 / kRatio, 0.5}, {.law = ElasticLaw::linear});
  const std::vector<Level>& l = q.levels;
  for (std::size_t i = 1; i < l.size(); ++i) {
    EXPECT_LT(l[i].err_force_filtered, l[i - 1].err_force_filtered) << "level " << i;
    EXPECT_LT(std::abs(l[i].err_duration), std::abs(l[i - 1].err_duration)) << "level " << i;
  }
  for (const Level& x : l) EXPECT_NEAR(x.impulse_ratio, 1.0, 0.005) << "s " << x.s;
  EXPECT_GT(q.duration.order, 0.75);
  EXPECT_GT(q.peak_filtered.order, 0.0);
  hertz::expect_matches_finite_sphere(q, "linear block a/R 0.107", /*filtered=*/true);
  hertz::expect_finest_matches_finite_sphere(q, "linear block a/R 0.107");
  const hertz::FiniteSphere f = hertz::finite_sphere(q);
  EXPECT_NEAR(q.peak_filtered.limit, f.peak_filtered, 0.005);
  EXPECT_NEAR(q.duration.limit, f.duration, 0.005);
}

// Penalty independence at the converged level (issue 11, item 3): the finest level of the a/R =
// 0.15 block sequence (s = 1, 72 586 tetrahedra) at α = 10 and α = 30. The penalty layer's own
// compliance is about h/(4αa) of the approach (docs/physics.md, FEM/DEM point 3: 0.9 % at α = 10
// with h = 5.6 mm, a = 15 mm, 0.3 % at α = 30), i.e. about 0.25 % of the peak (peak ∝ K^{2/5});
// the issue asks the peak independent of α within 1 %. Measured (reports/fem/hertz_convergence.md):
// filtered peak +5.94 / +6.01 %, duration −5.37 / −5.43 % from Hertz at α = 10 / 30 (0.07 and
// 0.06 point apart). The raw peak is not α-independent (+6.79 / +8.53 %): the stiffer layer rings
// harder, which is why the gates hold the T/20-filtered peak; it is printed, not gated. Cost: 63 +
// 101 s of run CPU and 2 × 17 s of meshing (α = 30 takes 1.7× the steps: the step is
// contact-limited).
TEST(HertzPenalty, PeakAndDurationIndependentOfAlphaAtTheFinestLevel) {
  const double speed = hertz::speed_for(0.15, scenes::rubbery());
  const Level a10 = hertz::run_level(Setup::block, 1.0, speed, true, {.alpha = 10});
  const Level a30 = hertz::run_level(Setup::block, 1.0, speed, true, {.alpha = 30});
  for (const Level* l : {&a10, &a30}) {
    EXPECT_TRUE(l->failure.empty()) << l->failure;
    std::printf(
        "alpha %2.0f: tets %ld  run %.1f s CPU  peak %+.4f (filtered %+.4f)  duration %+.4f  "
        "impulse/2mv %.4f  (%ld steps, dt %.3g s)\n",
        l == &a10 ? 10.0 : 30.0, l->tets, l->cpu, l->err_force, l->err_force_filtered,
        l->err_duration, l->impulse_ratio, l->steps, l->dt);
  }
  EXPECT_EQ(a10.tets, a30.tets);  // the same mesh: only the penalty differs
  EXPECT_NEAR(a30.peak_filtered / a10.peak_filtered, 1.0, 0.01);
  EXPECT_NEAR(a30.duration / a10.duration, 1.0, 0.01);
  // Both rebound elastically (vibration keeps 0.01–0.02 % of the impulse on these meshes).
  EXPECT_NEAR(a10.impulse_ratio, 1.0, 0.005);
  EXPECT_NEAR(a30.impulse_ratio, 1.0, 0.005);
}

}  // namespace
}  // namespace asperity::fdem
