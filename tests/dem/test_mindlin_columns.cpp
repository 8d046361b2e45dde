// The staged Hertz–Mindlin law (dem/mindlin_columns.hpp: batches of contacts in columns, in copies
// for x86-64-v4, v3 and the baseline) against the law computed whole (dem/hertz_contact.hpp,
// hertz_contact<true>, with the geometry of the sphere force loop): equal bit for bit on random
// contacts, sticking and sliding, for every copy this CPU runs.
//
// Tolerance 0, not a round-off bound: the staged copies perform the same IEEE operations on the
// same values in the same order as the law computed whole, and none fuses a multiply-add
// (mindlin_columns.cpp and sphere_world.cpp are compiled with -ffp-contract=off,
// solver/CMakeLists.txt), so a difference in any bit is a change in the law's arithmetic: a term,
// its order or a rounding. The sphere packings' results rest on it: the staged loop gives the bits
// of the loop one contact after another. Checked both ways (7 December 2026): one dot product of
// the staged law reassociated fails every copy at the second contact of seed 1 (a spring 1 ulp
// off); mindlin_columns.cpp compiled with -ffp-contract=fast fails the v3 and v4 copies (FMA) at
// the first contact, the baseline's (no FMA in x86-64) passing.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "solver/contact/hertz_mindlin.hpp"
#include "solver/contact/tangential_spring.hpp"
#include "solver/dem/hertz_contact.hpp"
#include "solver/dem/mindlin_columns.hpp"

namespace asperity::dem {
namespace {

// One contact's inputs: two spheres, the pair's coefficients and its history.
struct Contact {
  Vec3 d;  // x_i − x_j, m
  double ri = 0, rj = 0;
  Vec3 vi, wi, vj, wj, v_end_i, v_end_j;
  contact::HertzMindlinCoefficients c;
  Vec3 spring;  // last step's, N
  double viscous = 0;
};

// What the law gives of one contact, and its history after the step.
struct Result {
  Vec3 force, normal_force, torque_i, torque_j, spring;
  double dissipated = 0, ratio = 0, viscous = 0;
};

// The law computed whole, with the sphere force loop's geometry (dem/sphere_world.cpp,
// pair_forces_each: the normal as one quotient, the arms at half the overlap).
Result whole(Contact k, double dt) {
  const double dist = std::sqrt(k.d.squaredNorm());
  const double overlap = k.ri + k.rj - dist;
  const Vec3 n = k.d * (1.0 / dist);
  const Vec3 arm1 = -(k.ri - 0.5 * overlap) * n;
  const Vec3 arm2 = (k.rj - 0.5 * overlap) * n;
  const Vec3 v_rel = (k.vi + k.wi.cross(arm1)) - (k.vj + k.wj.cross(arm2));
  const double rate_end = -(k.v_end_i - k.v_end_j).dot(n);
  const ContactOutcome c =
      hertz_contact<true>(k.c, n, overlap, v_rel, rate_end, k.spring, k.viscous, dt);
  return {.force = c.force,
          .normal_force = c.normal_force,
          .torque_i = arm1.cross(c.force),
          .torque_j = arm2.cross(c.force),
          .spring = k.spring,
          .dissipated = c.dissipated,
          .ratio = overlap * (1.0 / std::min(k.ri, k.rj)),
          .viscous = k.viscous};
}

// Whether the contact slides this step, and whether its normal force is clipped to zero (the
// branches the set must cover), by the law's own pure functions.
struct Regime {
  bool sliding = false, clipped = false, fresh = false;
};
Regime regime(const Contact& k, double dt) {
  const double dist = std::sqrt(k.d.squaredNorm()), overlap = k.ri + k.rj - dist;
  const Vec3 n = k.d * (1.0 / dist);
  const Vec3 arm1 = -(k.ri - 0.5 * overlap) * n, arm2 = (k.rj - 0.5 * overlap) * n;
  const Vec3 v_rel = (k.vi + k.wi.cross(arm1)) - (k.vj + k.wj.cross(arm2));
  const double rate_end = -(k.v_end_i - k.v_end_j).dot(n);
  const contact::HertzMindlinForce f =
      contact::hertz_mindlin(overlap, rate_end, v_rel - v_rel.dot(n) * n,
                             contact::rotate_into_tangent_plane(k.spring, n), dt, k.c);
  return {.sliding = f.tangential.sliding,
          .clipped = f.normal.force == 0,
          .fresh = k.spring == Vec3::Zero()};
}

// The same contacts staged: gathered into columns as the force loop gathers them
// (dem/sphere_world.cpp, gather_mindlin and set_mindlin_law), t per batch.
std::vector<Result> staged(MindlinColumnsFn law, const std::vector<Contact>& contacts,
                           std::size_t t, double dt) {
  std::vector<Result> out;
  for (std::size_t m0 = 0; m0 < contacts.size(); m0 += t) {
    MindlinColumns b{};
    double history[4][kColumn] = {};
    const std::size_t n = std::min(t, contacts.size() - m0);
    for (std::size_t m = 0; m < n; ++m) {
      const Contact& k = contacts[m0 + m];
      const double dist = std::sqrt(k.d.squaredNorm());
      for (int a = 0; a < 3; ++a) {
        b.d[a][m] = k.d[a];
        b.vi[a][m] = k.vi[a];
        b.wi[a][m] = k.wi[a];
        b.vj[a][m] = k.vj[a];
        b.wj[a][m] = k.wj[a];
        b.dv_end[a][m] = k.v_end_i[a] - k.v_end_j[a];
        history[a][m] = k.spring[a];
      }
      history[3][m] = k.viscous;
      b.dist[m] = dist;
      b.overlap[m] = k.ri + k.rj - dist;
      b.ri[m] = k.ri;
      b.rj[m] = k.rj;
      b.k[m] = k.c.normal.k;
      b.damping[m] = k.c.normal.damping;
      b.shear[m] = k.c.shear;
      b.shear_damping[m] = k.c.shear_damping;
      b.friction[m] = k.c.friction;
      b.inv_min_radius[m] = 1.0 / std::min(k.ri, k.rj);
    }
    law(b, n, dt, history[0], history[1], history[2], history[3]);
    for (std::size_t m = 0; m < n; ++m) {
      const auto col = [m](const double(&a)[3][kColumn]) {
        return Vec3(a[0][m], a[1][m], a[2][m]);
      };
      out.push_back({.force = col(b.force),
                     .normal_force = col(b.normal_force),
                     .torque_i = col(b.torque_i),
                     .torque_j = col(b.torque_j),
                     .spring = Vec3(history[0][m], history[1][m], history[2][m]),
                     .dissipated = b.dissipated[m],
                     .ratio = b.ratio[m],
                     .viscous = history[3][m]});
    }
  }
  return out;
}

// Random contacts of spheres 0.5–2 mm across materials from soft rubber to steel: overlaps from
// 1e-9 to 5e-2 of the smaller radius, approaching and separating (some fast enough to clip the
// normal force), relative motion per step dt from 10⁻³ to 3 overlaps, springs from none (a new
// contact) to 3.5 times the Coulomb limit, off the tangent plane (the rotation), some along the
// normal.
std::vector<Contact> random_contacts(std::uint64_t seed, int count, double dt) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto sym = [&](double a) { return a * (2 * u(rng) - 1); };
  const auto vec = [&](double a) { return Vec3(sym(a), sym(a), sym(a)); };
  const auto log_uniform = [&](double lo, double hi) { return lo * std::pow(hi / lo, u(rng)); };
  std::vector<Contact> out;
  for (int c = 0; c < count; ++c) {
    Contact k;
    k.ri = log_uniform(2.5e-4, 1e-3);
    k.rj = log_uniform(2.5e-4, 1e-3);
    const double young = log_uniform(1e7, 2e11), nu = 0.1 + 0.35 * u(rng);
    const double young_eff = young / (2 * (1 - nu * nu));
    const double shear_eff = young / (4 * (2 - nu) * (1 + nu));
    const double radius_eff = k.ri * k.rj / (k.ri + k.rj);
    const double mi = 2500 * 4.18879 * std::pow(k.ri, 3), mj = 2500 * 4.18879 * std::pow(k.rj, 3);
    k.c = contact::hertz_mindlin_coefficients({.young_eff = young_eff,
                                               .shear_eff = shear_eff,
                                               .radius_eff = radius_eff,
                                               .mass_eff = mi * mj / (mi + mj),
                                               .zeta = c % 7 == 0 ? 0.0 : 1.2 * u(rng),
                                               .friction = c % 11 == 0 ? 0.0 : u(rng)});
    const double overlap = std::min(k.ri, k.rj) * log_uniform(1e-9, 5e-2);
    const Vec3 dir = Vec3(sym(1), sym(1), sym(1)).normalized();
    k.d = (k.ri + k.rj - overlap) * dir;
    // Relative motion per step from 10⁻³ to 3 overlaps.
    const double speed = overlap / dt * log_uniform(1e-3, 3.0);
    k.vi = vec(speed);
    k.vj = vec(speed);
    k.wi = vec(speed / k.ri);
    k.wj = vec(speed / k.rj);
    k.v_end_i = k.vi + vec(0.1 * speed);
    k.v_end_j = k.vj + vec(0.1 * speed);
    // Springs scaled to the pair's Coulomb limit at this overlap (elastic part).
    const double limit = k.c.friction * k.c.normal.k * overlap * std::sqrt(overlap);
    switch (c % 5) {
      case 0:
        k.spring = Vec3::Zero();
        break;
      case 1:
        k.spring = (limit > 0 ? limit : 1e-3) * u(rng) * dir;  // along the normal
        break;
      case 2:
      case 3:
        k.spring = vec(0.6 * (limit > 0 ? limit : 1e-3));  // mostly within the limit
        break;
      default:
        k.spring = vec(2 * (limit > 0 ? limit : 1e-3));  // mostly past it
    }
    k.viscous = sym(0.1 * k.c.normal.k * overlap * std::sqrt(overlap));
    out.push_back(k);
  }
  return out;
}

std::string bits(double x) {
  char s[64];
  std::snprintf(s, sizeof s, "%a", x);
  return s;
}

// The first difference in any bit, named, or "".
std::string first_difference(const Result& a, const Result& b) {
  const auto same = [](double x, double y) {
    return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y);
  };
  const std::pair<const char*, const Vec3 Result::*> vectors[] = {
      {"force", &Result::force},
      {"normal_force", &Result::normal_force},
      {"torque_i", &Result::torque_i},
      {"torque_j", &Result::torque_j},
      {"spring", &Result::spring}};
  for (const auto& [name, field] : vectors) {
    for (int a3 = 0; a3 < 3; ++a3) {
      if (!same((a.*field)[a3], (b.*field)[a3])) {
        return std::string(name) + "[" + std::to_string(a3) + "] " + bits((a.*field)[a3]) + " vs " +
               bits((b.*field)[a3]);
      }
    }
  }
  const std::pair<const char*, double Result::*> scalars[] = {{"dissipated", &Result::dissipated},
                                                              {"ratio", &Result::ratio},
                                                              {"viscous", &Result::viscous}};
  for (const auto& [name, field] : scalars) {
    if (!same(a.*field, b.*field))
      return std::string(name) + " " + bits(a.*field) + " vs " + bits(b.*field);
  }
  return "";
}

TEST(MindlinColumns, EveryCopyGivesTheWholeLawsBits) {
  const std::pair<const char*, MindlinCopy> copies[] = {{"baseline", MindlinCopy::baseline},
                                                        {"x86-64-v3", MindlinCopy::x86_64_v3},
                                                        {"x86-64-v4", MindlinCopy::x86_64_v4}};
  int copies_run = 0;
  int sliding = 0, sticking = 0, clipped = 0, fresh = 0, total = 0;
  for (std::uint64_t seed : {1u, 2u, 3u, 2026u, 31337u}) {
    const double dt = 1e-7 * static_cast<double>(1 + seed % 10);
    const std::vector<Contact> contacts = random_contacts(seed, 200, dt);
    std::vector<Result> expected;
    for (const Contact& k : contacts) {
      expected.push_back(whole(k, dt));
      const Regime r = regime(k, dt);
      sliding += r.sliding;
      sticking += !r.sliding;
      clipped += r.clipped;
      fresh += r.fresh;
      ++total;
    }
    for (const auto& [name, copy] : copies) {
      const MindlinColumnsFn law = mindlin_columns_copy(copy);
      if (law == nullptr) continue;
      copies_run += seed == 1;
      // Batches of the force loop's size, and ragged ones (the vector loops' remainders).
      for (std::size_t t : {kBatch, std::size_t{29}, std::size_t{7}, std::size_t{1}}) {
        const std::vector<Result> got = staged(law, contacts, t, dt);
        ASSERT_EQ(got.size(), expected.size());
        for (std::size_t m = 0; m < got.size(); ++m) {
          const std::string diff = first_difference(got[m], expected[m]);
          EXPECT_EQ(diff, "") << name << ", seed " << seed << ", batches of " << t << ", contact "
                              << m;
          if (!diff.empty()) break;  // one report per copy and batching
        }
      }
    }
    // The copy the force loop runs.
    const std::vector<Result> got = staged(mindlin_columns(), contacts, kBatch, dt);
    for (std::size_t m = 0; m < got.size(); ++m) {
      ASSERT_EQ(first_difference(got[m], expected[m]), "") << "seed " << seed << ", contact " << m;
    }
  }
  EXPECT_GE(copies_run, 1);
  // The set covers both sides of the Coulomb test, the clipped normal force and new contacts.
  EXPECT_GT(sliding, total / 5);
  EXPECT_GT(sticking, total / 5);
  EXPECT_GT(clipped, 0);
  EXPECT_GT(fresh, 0);
  std::printf("copies run: %d; %d contacts: %d sliding, %d sticking, %d clipped, %d new\n",
              copies_run, total, sliding, sticking, clipped, fresh);
}

}  // namespace
}  // namespace asperity::dem
