// The source reference's plan and terms (study/source_reference.hpp): the levels' sizes against
// the source's own triangles at the contact; the Richardson limit of the levels
// on the patch, the patch check's change (the doubled patch's levels extrapolated with the
// patch's order and weight) and the uncertainty, on synthetic level sequences whose order, limit
// and offset are known, so every number asserted is exact to round-off.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "solver/geometry/geodesic_sphere.hpp"
#include "solver/geometry/refined_sphere.hpp"
#include "solver/run/impact_measures.hpp"
#include "study/source_reference.hpp"
#include "study/tables/study_cases.hpp"
#include "tests/study/gate_particle.hpp"

namespace asperity::study::source_reference_terms_tests {
namespace {

// The plan's three levels h, h/2, h/4 (over R): a/3 at a/R = 0.065, the measured median.
const std::vector<double> kSizes = {0.0867, 0.04333, 0.02167};

// A level sequence converging as L + c h^p in every metric (the impulse and the duration scaled,
// so the three metrics are not one number).
std::vector<SourceLevel> levels(double limit, double c, double p) {
  std::vector<SourceLevel> v;
  for (double h : kSizes) {
    const double x = limit + c * std::pow(h, p);
    v.push_back({.peak_force = x, .impulse = 1e-3 * x, .contact_duration = 1e-6 * x});
  }
  return v;
}

// Round-off bound of the relative changes below: the limits are sums of a few terms of size
// about 1000 (N), each exact to 1e-16 relative; 1e-12 leaves a thousand times that.
constexpr double kRoundOff = 1e-12;

TEST(SourceReferenceTerms, ConstantOffsetOfTheDoubledPatchIsTheChangeExactly) {
  // The doubled patch's levels the patch's plus a constant 0.7 % of the limit: whatever the
  // weights, a weighted extrapolation whose weights sum to 1 moves by exactly that offset.
  const double limit = 1000, p = 1.6;
  const std::vector<SourceLevel> patch = levels(limit, 4000, p);
  std::vector<SourceLevel> doubled = patch;
  for (SourceLevel& l : doubled) {
    l.peak_force += 7.0;
    l.impulse += 7e-3;
    l.contact_duration += 7e-6;
  }
  const SourceReference r = source_reference(kSizes, patch, doubled);
  for (const SourceMetric* m : {&r.peak_force, &r.impulse, &r.contact_duration}) {
    EXPECT_TRUE(m->limit.observed);
    EXPECT_NEAR(m->limit.order, p, 1e-9);  // the bisection's 2^-100 of its bracket
    EXPECT_NEAR(m->patch_change, 0.007, kRoundOff);
    // The uncertainty: the extrapolation's estimated error, the patch term and (peak force
    // only) the filter's term in quadrature.
    EXPECT_NEAR(m->uncertainty, std::hypot(m->limit.error, 0.007, m->filter), kRoundOff);
  }
  EXPECT_NEAR(r.peak_force.limit.limit, limit, 1e-9);
}

TEST(SourceReferenceTerms, AlternatingLevelDifferencesAreWeightedAtThePatchOrder) {
  // The doubled patch's levels differ from the patch's by an offset c plus ±e alternating from
  // level to level (what gen7321 showed: ±0.2–0.7 %). At the patch's order p the last change is
  // weighted w = 1/(2^p − 1), so the doubled limit is the patch's + c + e (1 + 2w) (the finest
  // level's +e, the change's 2e times w); its own sequence would be extrapolated otherwise.
  const double limit = 1000, p = 2.0, c = 5.0, e = 4.0;
  const std::vector<SourceLevel> patch = levels(limit, 4000, p);
  std::vector<SourceLevel> doubled = patch;
  const double signs[] = {+1, -1, +1};
  for (std::size_t k = 0; k < doubled.size(); ++k) doubled[k].peak_force += c + signs[k] * e;
  const SourceReference r = source_reference(kSizes, patch, doubled);
  const double w = 1 / (std::pow(kSizes[1] / kSizes[2], p) - 1);
  ASSERT_TRUE(r.peak_force.limit.observed);
  EXPECT_NEAR(r.peak_force.limit.weight, w, 1e-9);
  EXPECT_NEAR(r.peak_force.patch_change, (c + e * (1 + 2 * w)) / limit, 1e-11);
  // The doubled levels alone (1039.1, 1008.5, 1010.9 N at these numbers) oscillate: their own
  // extrapolation falls back to the assumed bracket, another weight, another change.
  std::vector<double> own;
  for (const SourceLevel& l : doubled) own.push_back(l.peak_force);
  const tables::Extrapolation alone = tables::richardson(kSizes, own);
  EXPECT_FALSE(alone.observed);
  EXPECT_GT(std::abs(alone.limit / r.peak_force.limit.limit - 1 - r.peak_force.patch_change), 1e-4);
  // The other metrics had no offset: no change.
  EXPECT_NEAR(r.impulse.patch_change, 0, kRoundOff);
}

TEST(SourceReferenceTerms, AssumedOrderCarriesTheBracketWeightToTheDoubledPatch) {
  // Patch levels that overshoot (no observed order): the limit is the bracket's (orders 1.2 and
  // 2.7, tables::richardson), weight the mean of 1/(2^1.2 − 1) and 1/(2^2.7 − 1); the doubled
  // levels, offset by 3 and with a finest level 2 higher, take that weight.
  std::vector<SourceLevel> patch = {
      {.peak_force = 1100}, {.peak_force = 990}, {.peak_force = 1000}};
  std::vector<SourceLevel> doubled = {
      {.peak_force = 1103}, {.peak_force = 993}, {.peak_force = 1005}};
  const SourceReference r = source_reference(kSizes, patch, doubled);
  const double r2 = kSizes[1] / kSizes[2];
  const double w = 0.5 * (1 / (std::pow(r2, 1.2) - 1) + 1 / (std::pow(r2, 2.7) - 1));
  EXPECT_FALSE(r.peak_force.limit.observed);
  const double patch_limit = 1000 + w * 10, doubled_limit = 1005 + w * 12;
  EXPECT_NEAR(r.peak_force.limit.limit, patch_limit, 1e-9);
  EXPECT_NEAR(r.peak_force.patch_change, doubled_limit / patch_limit - 1, kRoundOff);
}

TEST(SourceReferenceTerms, WithoutTheDoubledPatchTheUncertaintyIsTheExtrapolationsError) {
  const SourceReference r = source_reference(kSizes, levels(1000, 4000, 1.3), {});
  EXPECT_TRUE(std::isnan(r.peak_force.patch_change));
  EXPECT_DOUBLE_EQ(r.peak_force.discretization, r.peak_force.limit.error);
  // Roache's 1.25 times the last correction c h3^p over the limit (tables::richardson).
  EXPECT_NEAR(r.peak_force.discretization, 1.25 * 4000 * std::pow(kSizes[2], 1.3) / 1000, 1e-9);
  EXPECT_DOUBLE_EQ(r.peak_force.uncertainty,
                   std::hypot(r.peak_force.limit.error, r.peak_force.filter));
  EXPECT_DOUBLE_EQ(r.impulse.uncertainty, r.impulse.limit.error);
}

TEST(SourceReferenceTerms, ATermNotMeasuredCountsZeroInTheQuadrature) {
  // tables::quadrature_sum, the one sum of the references' terms: the patch check not run (NaN)
  // adds nothing, and the sum is the nested two-term hypot the references' table always wrote.
  EXPECT_EQ(tables::quadrature_sum(0.003, std::nan("")), 0.003);
  EXPECT_EQ(tables::quadrature_sum(std::nan(""), -0.004), 0.004);
  EXPECT_EQ(tables::quadrature_sum(0.003, 0.004), std::hypot(0.003, 0.004));
}

TEST(SourceReferenceTerms, ASlowlyConvergingReferenceCarriesItsDistanceToTheLimit) {
  // Levels L + c h^0.24, ballast_01's measured order in peak force (changes −217, −183 N):
  // below the 0.5 richardson trusts, so its limit is the assumed bracket's (orders 1.2–2.7),
  // short of L by several times the bracket's own spread. The reference's discretization term
  // must cover the true distance |L − limit| / limit, which the levels' own order recovers
  // exactly on an exact power law (to the order's bisection, 1e-28, and round-off).
  const double limit = 14675, c = 2400, p = 0.24;
  const SourceReference r = source_reference(kSizes, levels(limit, c, p), {});
  const SourceMetric& m = r.peak_force;
  ASSERT_FALSE(m.limit.observed);
  EXPECT_NEAR(m.limit.changes_order, p, 1e-9);
  const double truth = std::abs(limit - m.limit.limit) / m.limit.limit;
  EXPECT_GT(truth, 2 * m.limit.error);  // the bracket's spread alone would understate it
  EXPECT_NEAR(m.discretization, truth, kRoundOff);
  EXPECT_DOUBLE_EQ(m.uncertainty, std::hypot(m.discretization, m.filter));  // no patch check
  // A sequence at an observed order keeps richardson's error unchanged.
  const SourceReference q = source_reference(kSizes, levels(1000, 4000, 1.3), {});
  EXPECT_DOUBLE_EQ(q.peak_force.discretization, q.peak_force.limit.error);
}

TEST(SourceReferenceTerms, AnUntrustedOrderCarriesAtLeastTheLastChange) {
  // rock_04's filtered peaks (6 December 2026): −2.0 %, then +0.15 %: no observed order, the
  // bracket's limit, and a discretization term of at least the last change over the limit, where
  // the bracket's half spread alone is about 0.3 of it.
  std::vector<SourceLevel> patch = {
      {.peak_force = 176910}, {.peak_force = 173370}, {.peak_force = 173637}};
  const SourceReference r = source_reference(kSizes, patch, {});
  ASSERT_FALSE(r.peak_force.limit.observed);
  EXPECT_LT(r.peak_force.limit.error, 0.5 * 267 / r.peak_force.limit.limit);
  // The band at the sizes' last ratio, 1.9995: 3 / (r² − 1) = 1.0006 last changes.
  const double r2 = kSizes[1] / kSizes[2], band = 3 / (r2 * r2 - 1);
  EXPECT_NEAR(r.peak_force.discretization, band * 267 / r.peak_force.limit.limit, kRoundOff);
  // Changes of one sign at a trusted order keep richardson's error.
  const SourceReference q = source_reference(kSizes, levels(1000, 4000, 1.3), {});
  EXPECT_DOUBLE_EQ(q.peak_force.discretization, q.peak_force.limit.error);
  // An order above the trusted range (E34's filtered peaks at a/1.5, a/3, a/6: order 6.86): at
  // least the last change too.
  std::vector<SourceLevel> steep = {
      {.peak_force = 66907}, {.peak_force = 62739}, {.peak_force = 62703}};
  const SourceReference e = source_reference(kSizes, steep, {});
  ASSERT_FALSE(e.peak_force.limit.observed);
  EXPECT_GT(e.peak_force.limit.changes_order, 6.8);
  EXPECT_NEAR(e.peak_force.discretization, band * 36 / e.peak_force.limit.limit, kRoundOff);
}

// A fourth level (wants_finer_level): where the three levels' peak force shows no steady order,
// [kSteadyOrderMin, kSteadyOrderMax] = [1, 4] (below it, oscillating, or above it), and leaves the
// limit uncertain by more than kFinerLevelAbove, 1 %.
TEST(SourceReferenceLevels, AFourthLevelWhereThePeakShowsNoSteadyOrder) {
  const auto power = [](double limit, double c, double p) {
    std::vector<double> v;
    for (double h : kSizes) v.push_back(limit + c * std::pow(h, p));
    return v;
  };
  // rock_04-o1's three levels (reports/study-wide-source): changes +975, +913 N, order 0.09.
  const std::vector<double> rock04 = {99100, 100075, 100988};
  EXPECT_NEAR(tables::richardson(kSizes, rock04).changes_order, 0.09, 0.01);
  EXPECT_TRUE(wants_finer_level(kSizes, rock04));
  // ballast_01-o1's order, 0.76: trusted by the extrapolation (≥ 0.5), not steady (< 1).
  EXPECT_TRUE(wants_finer_level(kSizes, power(6700, -2400, 0.76)));
  // Order 2 (and 1.2, 3.5): steady, three levels are enough.
  EXPECT_FALSE(wants_finer_level(kSizes, power(100000, 1e6, 2)));
  EXPECT_FALSE(wants_finer_level(kSizes, power(100000, 1e6, 1.2)));
  EXPECT_FALSE(wants_finer_level(kSizes, power(100000, 1e6, 3.5)));
  // Alternating changes (rock_04's at the finest resolution: −2.0 %, +0.15 %) have no order, but
  // their term is the last change, 0.15 %: within 1 %, no fourth level. The same shape scaled to a
  // last change of 1.5 % wants one.
  EXPECT_FALSE(wants_finer_level(kSizes, {176910, 173370, 173637}));
  EXPECT_TRUE(wants_finer_level(kSizes, {176910, 170000, 172550}));
  // Growing changes (the last 2 %) want one; an order above 4 (E34's, 6.86) whose last change is
  // 0.06 % does not, while the same steep fall ending in a 3 % change does.
  EXPECT_TRUE(wants_finer_level(kSizes, {1000, 1010, 1030}));
  EXPECT_FALSE(wants_finer_level(kSizes, {66907, 62739, 62703}));
  EXPECT_TRUE(wants_finer_level(kSizes, {200000, 100000, 97000}));
  // Two levels show no order to judge: the first round is never cut short.
  EXPECT_FALSE(wants_finer_level({kSizes[0], kSizes[1]}, {99100, 100075}));
  // The fourth size is half the third's; the first three are the plan's own.
  EXPECT_DOUBLE_EQ(level_size(kSizes, 2), kSizes[1]);
  EXPECT_DOUBLE_EQ(level_size(kSizes, 4), kSizes[2] / 2);
}

// With four levels the reference is the Richardson limit of the last three: levels 2-4 at
// L + c h² (L = 1000 N, c = 30 000 N/R² at h = 0.04, 0.02, 0.01 R: 1048, 1012, 1003 N) after a
// first level (1060 N) that is no point of that ladder, so that the first three's changes grow
// (−12, −36 N: no order, the last 3.6 % of the peak) and want the fourth. By hand: observed order
// log2(36/9) = 2, limit 1003 − 9/(2² − 1) = 1000 N, error 1.25 × 3/1000. The first three alone
// would give the bracket's limit, 1012 − 36/(2^1.95 − 1) = 999.43 N.
TEST(SourceReferenceLevels, FourLevelsGiveTheLimitOfTheLastThree) {
  const std::vector<double> sizes = {0.08, 0.04, 0.02, 0.01};
  std::vector<SourceLevel> patch, doubled;
  for (double h : sizes) {
    const double x = h > 0.05 ? 1060 : 1000 + 30000 * h * h;
    patch.push_back({.peak_force = x, .impulse = 1e-3 * x, .contact_duration = 1e-6 * x});
    doubled.push_back(
        {.peak_force = x + 4, .impulse = 1e-3 * (x + 4), .contact_duration = 1e-6 * (x + 4)});
  }
  ASSERT_TRUE(wants_finer_level({sizes[0], sizes[1], sizes[2]},
                                {patch[0].peak_force, patch[1].peak_force, patch[2].peak_force}));
  const SourceReference r = source_reference(sizes, patch, doubled);
  // The order by bisection to 2^-100 of [1e-3, 20] and sums of a few terms of about 1000 N:
  // round-off (kRoundOff relative) bounds both.
  EXPECT_TRUE(r.peak_force.limit.observed);
  EXPECT_NEAR(r.peak_force.limit.order, 2, 1e-9);
  EXPECT_NEAR(r.peak_force.limit.limit, 1000, 1000 * kRoundOff);
  EXPECT_NEAR(r.peak_force.limit.error, 1.25 * 3 / 1000, kRoundOff);
  EXPECT_NEAR(r.impulse.limit.limit, 1, kRoundOff);
  // The doubled patch 4 N above at every level: its limit at the patch's weight 4 N above too.
  EXPECT_NEAR(r.peak_force.patch_change, 4.0 / 1000, kRoundOff);
  // Not the first three's limit.
  const SourceReference first =
      source_reference({sizes[0], sizes[1], sizes[2]}, {patch[0], patch[1], patch[2]}, {});
  EXPECT_GT(std::abs(first.peak_force.limit.limit - 1000), 0.4);
}

// A level's peak is its ringing-free peak (source_level): the filtered peak over 1 minus the
// filter's bias on Hertz's pulse, 0.169 %; the reference's peak force carries the bias's
// dependence on the pulse's shape, Hertz's less a half-sine's (0.066 %), in its uncertainty, and
// the other metrics carry nothing of the filter. Exact to round-off.
TEST(SourceReferenceTerms, ThePeakIsRingingFreeAndCarriesTheFiltersShapeTerm) {
  const SourceLevel l = source_level(1000, 2, 3e-4);
  EXPECT_NEAR(l.peak_force, 1000 / (1 - run::kFilteredPeakBiasHertz), kRoundOff * 1000);
  EXPECT_NEAR(l.peak_force / 1000 - 1, 0.00169, 1e-5);  // (15/8) 2.9433² / 9600
  EXPECT_EQ(l.impulse, 2);
  EXPECT_EQ(l.contact_duration, 3e-4);
  const SourceReference r = source_reference(kSizes, levels(1000, 4000, 1.3), {});
  EXPECT_NEAR(r.peak_force.filter, 0.00066, 1e-5);
  EXPECT_EQ(r.impulse.filter, 0);
  EXPECT_EQ(r.contact_duration.filter, 0);
}

// The plan's sizes on two generated particles whose contact spans different numbers of source
// triangles (20 480 and 1280 faces, the set's shape numbers): every level at most the source's
// own edge at the contact, so each refines the contact surface (the mesher bisects the surface
// only where the size is below its triangles; ballast_01's a/0.75 level left the strike point's
// fan of 7 vertices as the whole contact: docs/study.md), and at most a / kCoarsestAcross (1.5
// elements across the contact radius); the coarsest no finer than needed (the next coarser would
// exceed one of the two, or it is the a/elements_across ladder itself); the finest at most a/3
// (issue 28: at least 3 elements across Hertz's contact radius at peak); halving.
TEST(SourceReferencePlan, EveryLevelRefinesTheSourcesOwnTrianglesAtTheContact) {
  const Material rock{.name = "rock", .density = 2650, .young = 50e9, .poisson = 0.25};
  for (long faces : {20480L, 1280L}) {
    const SurfaceMesh source = test::gate_particle_7321(faces);
    const SourceReferenceOptions options{};
    const SourceReferencePlan plan = plan_source_reference(source, rock, 2.0, options);
    ASSERT_EQ(plan.sizes.size(), 3u) << faces;
    const double ladder = plan.contact_radius / options.elements_across;  // the finest asked for
    EXPECT_GT(plan.contact_edge, 0) << faces;
    // Both sources here are coarser than the finest size (ballast-like, 20 480 or 1280 faces).
    ASSERT_GT(plan.contact_edge, std::sqrt(2.0) * ladder) << faces;
    const double within = std::min(plan.contact_edge, plan.contact_radius / kCoarsestAcross);
    EXPECT_LE(plan.sizes.front(), within * (1 + kRoundOff)) << faces;
    EXPECT_TRUE(2 * plan.sizes.front() > within ||
                std::abs(plan.sizes.back() - ladder) <= kRoundOff * ladder)
        << faces << ": coarsest " << plan.sizes.front() << " m, contact edge " << plan.contact_edge
        << " m";
    EXPECT_LE(plan.sizes.back(), ladder * (1 + kRoundOff)) << faces;
    for (std::size_t k = 1; k < plan.sizes.size(); ++k) {
      EXPECT_NEAR(plan.sizes[k - 1], 2 * plan.sizes[k], kRoundOff * plan.sizes[k]) << faces;
    }
    std::printf("%ld faces: a %.4g m, contact edge %.4g m (a/%.3g), sizes a/%.3g .. a/%.3g\n",
                faces, plan.contact_radius, plan.contact_edge,
                plan.contact_radius / plan.contact_edge, plan.contact_radius / plan.sizes.front(),
                plan.contact_radius / plan.sizes.back());
  }
}

// A source finer than the finest size at the contact keeps the ladder a/elements_across · (4, 2,
// 1): the sphere of SphereStudy.SourceReferenceConvergesTowardsTheFiniteSphere (a 25 mm icosphere
// bisected to 0.0167 R facets within 0.15 R of its lowest vertex, its levels' order 2.95 so), whose
// every level has its own fine triangles across the contact; halving it would cost 8-10 times more
// for nothing.
TEST(SourceReferencePlan, ASourceFinerThanTheFinestLevelKeepsTheLadder) {
  constexpr double kRadius = 0.025;
  SurfaceMesh ico = geometry::geodesic_sphere(8);
  ico.vertices *= kRadius;
  const SurfaceMesh source = geometry::refined_sphere(8, kRadius, 0.0167 * kRadius, 0.15 * kRadius,
                                                      geometry::lowest_vertex(ico));
  const Material rock{.name = "rock", .density = 2650, .young = 50e9, .poisson = 0.3};
  const SourceReferenceOptions options{};
  const SourceReferencePlan plan = plan_source_reference(source, rock, 1.25, options);
  const double ladder = plan.contact_radius / options.elements_across;
  EXPECT_LE(plan.contact_edge, std::sqrt(2.0) * ladder);
  ASSERT_EQ(plan.sizes.size(), 3u);
  EXPECT_NEAR(plan.sizes.back(), ladder, kRoundOff * ladder);
  EXPECT_NEAR(plan.sizes.front(), 4 * ladder, kRoundOff * ladder);
  std::printf("sphere: a %.4g R, contact edge %.4g R (a/%.3g), finest a/%.3g\n",
              plan.contact_radius / kRadius, plan.contact_edge / kRadius,
              plan.contact_radius / plan.contact_edge, plan.contact_radius / plan.sizes.back());
}

}  // namespace
}  // namespace asperity::study::source_reference_terms_tests
