// Rigid-sphere DEM step: broad phase (Verlet list on a cell grid) → contact forces → integrate.
#include "solver/dem/sphere_world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include "solver/contact/hertz.hpp"
#include "solver/contact/hertz_mindlin.hpp"
#include "solver/contact/linear_spring_dashpot.hpp"
#include "solver/contact/tangential_spring.hpp"
#include "solver/core/error.hpp"
#include "solver/core/ticks.hpp"
#include "solver/dem/cell_grid.hpp"
#include "solver/dem/hertz_contact.hpp"
#include "solver/dem/mindlin_columns.hpp"

namespace asperity::dem {
namespace {

// What one contact needs, whatever the pair: geometry and the effective quantities.
struct ContactGeometry {
  Vec3 normal;        // unit, from body 2 towards body 1
  double overlap;     // m
  Vec3 arm1, arm2;    // contact point relative to each centre, m
  double radius_eff;  // R*, m
  double mass_eff;    // m*, kg
};

contact::HertzMindlinCoefficients coefficients_of(const PairConstants& pc,
                                                  const ContactGeometry& g) {
  return contact::hertz_mindlin_coefficients({.young_eff = pc.young_eff,
                                              .shear_eff = pc.shear_eff,
                                              .radius_eff = g.radius_eff,
                                              .mass_eff = g.mass_eff,
                                              .zeta = pc.zeta,
                                              .friction = pc.friction});
}

contact::LinearParams linear_params(const SphereWorld& world, const PairConstants& pc,
                                    double mass_eff) {
  return {.kn = world.law.kn, .mass_eff = mass_eff, .zeta = pc.zeta};
}

// Normal and tangential force on body 1 for one touching contact of any law: the scene's law (a
// pure function in contact/) applied to this pair's geometry, effective quantities and history.
// The sphere pairs of the Hertz laws take their coefficients from the neighbour list instead
// (pair_forces).
ContactOutcome contact_force(const SphereWorld& world, const ContactGeometry& g,
                             const PairConstants& pc, const Vec3& v_rel, double rate_end,
                             Vec3& spring, double& viscous, double dt) {
  const Vec3& n = g.normal;
  if (world.law.normal == contact::NormalLaw::hertz) {
    const contact::HertzMindlinCoefficients c = coefficients_of(pc, g);
    return world.law.tangential
               ? hertz_contact<true>(c, n, g.overlap, v_rel, rate_end, spring, viscous, dt)
               : hertz_contact<false>(c, n, g.overlap, v_rel, rate_end, spring, viscous, dt);
  }
  const double rate = -v_rel.dot(n);
  const Vec3 slip = v_rel - v_rel.dot(n) * n;
  const contact::NormalForce fn =
      contact::linear_normal(g.overlap, rate_end, linear_params(world, pc, g.mass_eff));
  // The linear law's tangential spring: constant k_t, dashpot ζ √(m* k_t).
  const contact::TangentialForce ft =
      contact::tangential_spring(contact::rotate_into_tangent_plane(spring, n), slip, dt, fn.force,
                                 {.stiffness = world.law.kt,
                                  .damping = pc.zeta * std::sqrt(g.mass_eff * world.law.kt),
                                  .friction = pc.friction});
  return outcome(fn, ft, n, rate, spring, viscous, dt);
}

// Elastic energy stored in one touching contact at its overlap, J: the normal law's, plus the
// tangential spring's |F_s|²/(2 k_t) with the k_t the step used at this overlap.
double stored_energy(const SphereWorld& world, const contact::HertzMindlinCoefficients& c,
                     const PairConstants& pc, double overlap, const Vec3& spring) {
  if (world.law.normal == contact::NormalLaw::hertz) {
    const double normal = contact::hertz_normal(overlap, 0.0, c.normal).energy;
    return normal + (world.law.tangential
                         ? contact::spring_energy(spring, contact::mindlin_stiffness(c, overlap))
                         : 0.0);
  }
  return contact::linear_normal(overlap, 0.0, linear_params(world, pc, c.mass_eff)).energy +
         contact::spring_energy(spring, world.law.kt);
}

// The constants of candidate pair (i, j) (sphere_world.hpp, PairLaw).
PairLaw pair_law(const SphereWorld& w, int i, int j) {
  const int nm = static_cast<int>(w.materials.size());
  const double mi = w.fixed[i] ? 0 : w.mass[i], mj = w.fixed[j] ? 0 : w.mass[j];
  const ContactGeometry g{.radius_eff = w.radius[i] * w.radius[j] / (w.radius[i] + w.radius[j]),
                          .mass_eff = mi == 0 ? mj : (mj == 0 ? mi : mi * mj / (mi + mj))};
  return {.hertz = coefficients_of(w.pair[w.material[i] * nm + w.material[j]], g),
          .inv_min_radius = 1.0 / std::min(w.radius[i], w.radius[j])};
}

void rebuild_pairs(SphereWorld& world) {
  const std::vector<PairContact> old = std::move(world.pairs);
  const PairHistory old_history = std::move(world.history);
  world.pairs = neighbour_pairs(world.x, world.radius, world.fixed, world.skin);
  world.history.resize(world.pairs.size());
  // Carry the tangential history across (both lists sorted by (i, j)).
  std::size_t o = 0;
  for (std::size_t k = 0; k < world.pairs.size(); ++k) {
    const PairContact& p = world.pairs[k];
    while (o < old.size() && std::tie(old[o].i, old[o].j) < std::tie(p.i, p.j)) ++o;
    if (o < old.size() && old[o].i == p.i && old[o].j == p.j) {
      for (int a = 0; a < 3; ++a) world.history.spring[a][k] = old_history.spring[a][o];
      world.history.viscous[k] = old_history.viscous[o];
    }
  }
  // One entry per distinct (materials, radii, masses as the law sees them), in order of first use.
  using Key = std::tuple<int, int, double, double, double, double>;
  std::map<Key, int> index;
  world.laws.clear();
  for (PairContact& p : world.pairs) {
    const int i = p.i, j = p.j;
    const Key key{world.material[i],
                  world.material[j],
                  world.radius[i],
                  world.radius[j],
                  world.fixed[i] ? 0.0 : world.mass[i],
                  world.fixed[j] ? 0.0 : world.mass[j]};
    const auto [at, added] = index.try_emplace(key, static_cast<int>(world.laws.size()));
    if (added) world.laws.push_back(pair_law(world, i, j));
    p.law = at->second;
  }
  world.x_at_build = world.x;
  ++world.rebuilds;
}

enum class PairLawKind { hertz_mindlin, hertz, linear };

// A candidate pair apart (|d|² = d2, reach the sum of the radii; dist: |d| if it was taken, else
// 0). Its gap is output only where it would raise a body's largest overlap (the gap reach − |d|
// exceeds s where |d|² < (reach − s)²): the root is taken for those alone. Its history is
// cleared only where it holds something: a candidate that stays apart costs no store.
void apart(SphereWorld& w, std::size_t k, int bi, int bj, double d2, double reach, double dist) {
  std::vector<double>& touch = w.contacts.overlap;
  if (const double s = std::min(touch[bi], touch[bj]); dist > 0 || d2 < (reach - s) * (reach - s)) {
    const double gap = reach - (dist > 0 ? dist : std::sqrt(d2));
    touch[bi] = std::max(touch[bi], gap);
    touch[bj] = std::max(touch[bj], gap);
  }
  PairHistory& h = w.history;
  if (h.viscous[k] != 0 || h.spring[0][k] != 0 || h.spring[1][k] != 0 || h.spring[2][k] != 0) {
    for (std::vector<double>& c : h.spring) c[k] = 0;
    h.viscous[k] = 0;
  }
}

// Sphere–sphere contacts of the candidate pairs, one after another (the Hertz and linear laws;
// Hertz–Mindlin's are staged: mindlin_pair_forces). The list is sorted by i: sphere i's force,
// torque and contact output are summed in registers over its run of pairs and stored once (the
// same sums in the same order as adding into the arrays pair by pair, without a store and reload
// per pair). The spheres' contact force output is their force total (compute_forces).
template <PairLawKind kind>
void pair_forces_each(SphereWorld& w, double dt) {
  static_assert(kind != PairLawKind::hertz_mindlin, "Hertz–Mindlin is mindlin_pair_forces'");
  const int nm = static_cast<int>(w.materials.size());
  const std::size_t np = w.pairs.size();
  std::vector<double>& touch = w.contacts.overlap;
  for (std::size_t k = 0; k < np;) {
    const int i = w.pairs[k].i, bi = w.body[i];
    const Vec3 xi = w.x.col(i), vi = w.v.col(i), wi = w.w.col(i), vei = w.v_end.col(i);
    const double ri = w.radius[i];
    Vec3 fi = w.force.col(i), ti = w.torque.col(i), fni = w.contacts.normal_force.col(bi);
    for (; k < np && w.pairs[k].i == i; ++k) {
      const PairContact& p = w.pairs[k];
      const int j = p.j, bj = w.body[j];
      const Vec3 d = xi - w.x.col(j);
      const double reach = ri + w.radius[j], d2 = d.squaredNorm();
      const double dist = d2 < reach * reach ? std::sqrt(d2) : 0.0;  // apart: no root yet
      const double overlap = reach - dist;
      if (dist == 0 || overlap <= 0) {
        apart(w, k, bi, bj, d2, reach, dist);
        continue;
      }
      Vec3 spring = w.history.spring_of(k);
      double& viscous = w.history.viscous[k];
      const PairLaw& law = w.laws[p.law];
      const Vec3 n = d * (1.0 / dist);  // one quotient, not three
      w.max_overlap_ratio = std::max(w.max_overlap_ratio, overlap * law.inv_min_radius);
      const Vec3 arm1 = -(ri - 0.5 * overlap) * n;
      const Vec3 arm2 = (w.radius[j] - 0.5 * overlap) * n;
      const Vec3 v_rel = (vi + wi.cross(arm1)) - (w.v.col(j) + w.w.col(j).cross(arm2));
      const double rate_end = -(vei - w.v_end.col(j)).dot(n);
      ContactOutcome c;
      if constexpr (kind == PairLawKind::linear) {
        const ContactGeometry g{.normal = n,
                                .overlap = overlap,
                                .arm1 = arm1,
                                .arm2 = arm2,
                                .radius_eff = law.hertz.radius_eff,
                                .mass_eff = law.hertz.mass_eff};
        c = contact_force(w, g, w.pair[w.material[i] * nm + w.material[j]], v_rel, rate_end, spring,
                          viscous, dt);
      } else {
        c = hertz_contact<false>(law.hertz, n, overlap, v_rel, rate_end, spring, viscous, dt);
      }
      for (int a = 0; a < 3; ++a) w.history.spring[a][k] = spring[a];
      fi += c.force;
      w.force.col(j) -= c.force;
      ti += arm1.cross(c.force);
      w.torque.col(j) -= arm2.cross(c.force);
      w.dissipated += c.dissipated;
      ++w.contact_updates;
      fni += c.normal_force;
      w.contacts.normal_force.col(bj) -= c.normal_force;
      touch[bi] = std::max(touch[bi], overlap);
      touch[bj] = std::max(touch[bj], overlap);
    }
    w.force.col(i) = fi;
    w.torque.col(i) = ti;
    w.contacts.normal_force.col(bi) = fni;
  }
}

// Hertz–Mindlin sphere–sphere contacts (the law of the packings), staged over batches of pairs
// so that the roots of different contacts overlap. One contact's law is a chain of dependent roots
// and quotients (|d|, 1/|d|, δ^{1/2}, δ^{1/4}, the spring's rotation factor) some 150 cycles long
// and ~250 instructions wide: taken one contact after another (pair_forces_each), the core's
// reorder window holds about two contacts and waits on the chain. Each stage is a loop over the
// batch whose iterations do not depend on each other:
//   1. distances (stage_distances): the apart pairs' gap output and history; what the law reads
//      of the touching ones gathered into columns, one array per component (gather_mindlin);
//   2. the law over the columns, vectorised by the compiler: 8 contacts per instruction with
//      AVX-512 (mindlin_columns.hpp); it reads and writes the history (PairHistory, columns of the
//      list's own) in place where every pair of the batch touches, so that a dense packing's
//      history is neither gathered nor written back (4 stores per contact fewer: the core retires
//      one store per cycle, and the gather and write-back were half the loop's time);
//   3. the sums in list order (scatter_mindlin).
// Every contact takes the same operations on the same values as when computed whole, and the sums
// (force, torque, contact output, dissipated energy) are added in the order of the list, so the
// results are the same bit for bit; maxima (the overlap output, the largest overlap ratio) do not
// depend on order. BM_Packing10k mindlin: 1.50x the loop one contact after another, and 1.08x
// more with the history in place (docs/performance.md). The law's bits are pinned to
// hertz_contact<true>'s by tests/dem/test_mindlin_columns.cpp.

// Stage 1: pairs [k0, k1). Apart pairs: their gap output and cleared history (apart). Touching
// ones: their overlap output taken, and handed in list order to touching(t, k, d, dist, overlap),
// t counting them from 0. Returns how many.
template <class Touching>
std::size_t stage_distances(SphereWorld& w, std::size_t k0, std::size_t k1, Touching touching) {
  std::vector<double>& touch = w.contacts.overlap;
  std::size_t t = 0;
  for (std::size_t k = k0; k < k1; ++k) {
    const PairContact& p = w.pairs[k];
    const int i = p.i, j = p.j, bi = w.body[i], bj = w.body[j];
    const Vec3 d = w.x.col(i) - w.x.col(j);
    const double reach = w.radius[i] + w.radius[j], d2 = d.squaredNorm();
    const double dist = d2 < reach * reach ? std::sqrt(d2) : 0.0;  // apart: no root yet
    const double overlap = reach - dist;
    if (dist == 0 || overlap <= 0) {
      apart(w, k, bi, bj, d2, reach, dist);
      continue;
    }
    touch[bi] = std::max(touch[bi], overlap);
    touch[bj] = std::max(touch[bj], overlap);
    touching(t++, k, d, dist, overlap);
  }
  return t;
}

// The law's columns of contacts [m0, m1) of a batch.
void set_mindlin_law(const PairLaw& law, std::size_t m0, std::size_t m1, MindlinColumns& b) {
  for (std::size_t m = m0; m < m1; ++m) {
    b.k[m] = law.hertz.normal.k;
    b.damping[m] = law.hertz.normal.damping;
    b.shear[m] = law.hertz.shear;
    b.shear_damping[m] = law.hertz.shear_damping;
    b.friction[m] = law.hertz.friction;
    b.inv_min_radius[m] = law.inv_min_radius;
  }
}

// Stage 1's touching contact m of a batch (pair k): what the law reads of it,
// into the columns. With one_law (every candidate pair shares SphereWorld::laws[0]) the law's
// columns are left as set_mindlin_law set them.
void gather_mindlin(const SphereWorld& w, std::size_t m, std::size_t k, const Vec3& d, double dist,
                    double overlap, bool one_law, MindlinColumns& b) {
  const PairContact& p = w.pairs[k];
  const int i = p.i, j = p.j;
  for (int a = 0; a < 3; ++a) {
    b.d[a][m] = d[a];
    b.vi[a][m] = w.v(a, i);
    b.wi[a][m] = w.w(a, i);
    b.vj[a][m] = w.v(a, j);
    b.wj[a][m] = w.w(a, j);
    b.dv_end[a][m] = w.v_end(a, i) - w.v_end(a, j);
  }
  b.dist[m] = dist;
  b.overlap[m] = overlap;
  b.ri[m] = w.radius[i];
  b.rj[m] = w.radius[j];
  if (!one_law) set_mindlin_law(w.laws[p.law], m, m + 1, b);
}

// Stage 3: the batch's largest overlap ratio, and its sums in list order.
// pair[m]: the m-th touching contact's index in the pair list. The list is sorted by i: sphere
// i's force, torque and contact output are summed in registers over its run of pairs and stored
// once. The spheres' contact force output is their force total (compute_forces).
void scatter_mindlin(SphereWorld& w, const std::size_t* pair, std::size_t t,
                     const MindlinColumns& b) {
  double max_ratio = w.max_overlap_ratio;
  const auto col = [](const double(&a)[3][kColumn], std::size_t m) {
    return Vec3(a[0][m], a[1][m], a[2][m]);
  };
  double dissipated = w.dissipated;
  std::size_t m = 0;
  while (m < t) {
    const int i = w.pairs[pair[m]].i, bi = w.body[i];
    Vec3 fi = w.force.col(i), ti = w.torque.col(i), fni = w.contacts.normal_force.col(bi);
    for (; m < t && w.pairs[pair[m]].i == i; ++m) {
      const PairContact& p = w.pairs[pair[m]];
      max_ratio = std::max(max_ratio, b.ratio[m]);
      const int j = p.j, bj = w.body[j];
      const Vec3 f = col(b.force, m), fn = col(b.normal_force, m);
      fi += f;
      w.force.col(j) -= f;
      ti += col(b.torque_i, m);
      w.torque.col(j) -= col(b.torque_j, m);
      dissipated += b.dissipated[m];
      fni += fn;
      w.contacts.normal_force.col(bj) -= fn;
    }
    w.force.col(i) = fi;
    w.torque.col(i) = ti;
    w.contacts.normal_force.col(bi) = fni;
  }
  w.dissipated = dissipated;
  w.max_overlap_ratio = max_ratio;
  w.contact_updates += static_cast<long>(t);
}

void mindlin_pair_forces(SphereWorld& w, double dt) {
  std::size_t pair[kBatch];
  MindlinColumns columns;
  double history[4][kColumn];  // a batch's history, where some of its pairs are apart
  // A packing of one size and material has one law: its columns are set once, not per contact.
  const bool one_law = w.laws.size() == 1;
  if (one_law) set_mindlin_law(w.laws[0], 0, kBatch, columns);
  const MindlinColumnsFn law = mindlin_columns();  // this CPU's widest copy
  PairHistory& h = w.history;
  const std::size_t np = w.pairs.size();
  for (std::size_t k0 = 0; k0 < np; k0 += kBatch) {
    const std::size_t k1 = std::min(np, k0 + kBatch);
    const std::size_t t = stage_distances(
        w, k0, k1, [&](std::size_t m, std::size_t k, const Vec3& d, double dist, double overlap) {
          pair[m] = k;
          gather_mindlin(w, m, k, d, dist, overlap, one_law, columns);
        });
    if (t == k1 - k0) {
      // Every pair of the batch touches (a dense packing's usual batch): contact m is pair
      // k0 + m, and the law reads and writes its history in the list's columns.
      law(columns, t, dt, &h.spring[0][k0], &h.spring[1][k0], &h.spring[2][k0], &h.viscous[k0]);
    } else {
      for (std::size_t m = 0; m < t; ++m) {
        for (int a = 0; a < 3; ++a) history[a][m] = h.spring[a][pair[m]];
        history[3][m] = h.viscous[pair[m]];
      }
      law(columns, t, dt, history[0], history[1], history[2], history[3]);
      for (std::size_t m = 0; m < t; ++m) {
        for (int a = 0; a < 3; ++a) h.spring[a][pair[m]] = history[a][m];
        h.viscous[pair[m]] = history[3][m];
      }
    }
    scatter_mindlin(w, pair, t, columns);
  }
}

// Overlap (m) of a sphere (centre x, radius r) with a wall, and the wall's outward normal there.
double wall_overlap(const Wall& wall, const Vec3& x, double r, Vec3& normal) {
  if (wall.kind == WallKind::plane) {
    normal = wall.b;
    return r - (x - wall.a).dot(normal);
  }
  const Vec3 closest = x.cwiseMax(wall.a).cwiseMin(wall.b);
  const Vec3 diff = x - closest;
  const double dist = diff.norm();
  if (dist > 0) {
    normal = diff / dist;
    return r - dist;
  }
  // Centre inside the box: push out through the nearest face.
  const Vec3 lo = x - wall.a, hi = wall.b - x;
  Eigen::Index kl, kh;
  const double dl = lo.minCoeff(&kl), dh = hi.minCoeff(&kh);
  normal = Vec3::Zero();
  if (dl < dh)
    normal[kl] = -1;
  else
    normal[kh] = 1;
  return r + std::min(dl, dh);
}

// Sphere–wall contacts (planes and boxes) of every moving sphere.
void wall_forces(SphereWorld& w, double dt) {
  const int nm = static_cast<int>(w.materials.size());
  const int n = w.size();
  std::vector<double>& touch = w.contacts.overlap;
  for (std::size_t k = 0; k < w.walls.size(); ++k) {
    const Wall& wall = w.walls[k];
    // The wall's contact output, summed in registers over the spheres and stored once.
    Vec3 wf = w.contacts.force.col(wall.body), wfn = w.contacts.normal_force.col(wall.body);
    double ws = touch[wall.body];
    for (int i = 0; i < n; ++i) {
      if (w.fixed[i]) continue;
      WallContact& h = w.wall_contacts[k * n + i];
      Vec3 normal;
      const double overlap = wall_overlap(wall, w.x.col(i), w.radius[i], normal);
      if (overlap <= 0) {
        touch[w.body[i]] = std::max(touch[w.body[i]], overlap);
        ws = std::max(ws, overlap);
        if (h.viscous != 0 || h.spring != Vec3::Zero()) {
          h.spring.setZero();
          h.viscous = 0;
        }
        continue;
      }
      w.max_overlap_ratio = std::max(w.max_overlap_ratio, overlap / w.radius[i]);
      ContactGeometry g{.normal = normal,
                        .overlap = overlap,
                        .arm1 = -(w.radius[i] - 0.5 * overlap) * normal,
                        .arm2 = Vec3::Zero(),
                        .radius_eff = w.radius[i],
                        .mass_eff = w.mass[i]};
      const Vec3 v_rel = w.v.col(i) + w.w.col(i).cross(g.arm1);
      const double rate_end = -w.v_end.col(i).dot(normal);
      const ContactOutcome c = contact_force(w, g, w.pair[w.material[i] * nm + wall.material],
                                             v_rel, rate_end, h.spring, h.viscous, dt);
      w.force.col(i) += c.force;
      w.torque.col(i) += g.arm1.cross(c.force);
      w.dissipated += c.dissipated;
      ++w.contact_updates;
      // The sphere's contact force output is its force total (compute_forces); the wall's here.
      wf -= c.force;
      w.contacts.normal_force.col(w.body[i]) += c.normal_force;
      wfn -= c.normal_force;
      touch[w.body[i]] = std::max(touch[w.body[i]], overlap);
      ws = std::max(ws, overlap);
    }
    w.contacts.force.col(wall.body) = wf;
    w.contacts.normal_force.col(wall.body) = wfn;
    touch[wall.body] = ws;
  }
}

// The first half kick and the drift, and in the same sweep over the spheres what the force pass
// needs: the end-of-step velocity the dashpots see, predicted with last step's acceleration
// (v_{n+1} ≈ v_{n+½} + ½ dt a_n: a second-order estimate where the half-step velocity alone lags
// by ½ dt a and biases damped peaks and restitution at coarse steps), and the force totals
// cleared. Returns the largest squared displacement since the neighbour list was built.
double kick_drift(SphereWorld& w, double dt) {
  const bool listed = w.x_at_build.cols() == w.x.cols();
  double moved = listed ? 0.0 : std::numeric_limits<double>::infinity();
  for (int i = 0; i < w.size(); ++i) {
    if (!w.fixed[i]) {
      const Vec3 a = w.force.col(i) * w.inv_mass[i] + w.gravity;
      w.v.col(i) += 0.5 * dt * a;
      w.w.col(i) += 0.5 * dt * w.torque.col(i) * w.inv_inertia[i];
      w.x.col(i) += dt * w.v.col(i);
      w.v_end.col(i) = w.v.col(i) + 0.5 * dt * a;
      if (listed) moved = std::max(moved, (w.x.col(i) - w.x_at_build.col(i)).squaredNorm());
    }
    w.force.col(i).setZero();
    w.torque.col(i).setZero();
  }
  return moved;
}

// Contact forces at the current positions into the (cleared) force totals, and the contact output.
void compute_forces(SphereWorld& w, double dt) {
  w.contacts.reset(w.contacts.size());
  switch (w.law.normal == contact::NormalLaw::linear
              ? PairLawKind::linear
              : (w.law.tangential ? PairLawKind::hertz_mindlin : PairLawKind::hertz)) {
    case PairLawKind::hertz_mindlin:
      mindlin_pair_forces(w, dt);
      break;
    case PairLawKind::hertz:
      pair_forces_each<PairLawKind::hertz>(w, dt);
      break;
    case PairLawKind::linear:
      pair_forces_each<PairLawKind::linear>(w, dt);
      break;
  }
  wall_forces(w, dt);
  // A sphere is a scene body of its own, and all its contact forces are in its force total, summed
  // in the order its contacts were: its contact output is that total.
  for (int i = 0; i < w.size(); ++i) w.contacts.force.col(w.body[i]) = w.force.col(i);
}

// Elastic energy stored in every touching contact at the current positions and springs, J: what
// the last step's contacts hold, summed in the order the step met them.
double contact_energy(const SphereWorld& w) {
  const int nm = static_cast<int>(w.materials.size());
  double e = 0;
  for (std::size_t k = 0; k < w.pairs.size(); ++k) {
    const PairContact& p = w.pairs[k];
    const double dist = (w.x.col(p.i) - w.x.col(p.j)).norm();
    const double overlap = w.radius[p.i] + w.radius[p.j] - dist;
    if (overlap <= 0 || dist == 0) continue;
    e += stored_energy(w, w.laws[p.law].hertz, w.pair[w.material[p.i] * nm + w.material[p.j]],
                       overlap, w.history.spring_of(k));
  }
  const int n = w.size();
  for (std::size_t k = 0; k < w.walls.size(); ++k) {
    for (int i = 0; i < n; ++i) {
      if (w.fixed[i]) continue;
      Vec3 normal;
      const double overlap = wall_overlap(w.walls[k], w.x.col(i), w.radius[i], normal);
      if (overlap <= 0) continue;
      const PairConstants& pc = w.pair[w.material[i] * nm + w.walls[k].material];
      const ContactGeometry g{.radius_eff = w.radius[i], .mass_eff = w.mass[i]};
      e += stored_energy(w, coefficients_of(pc, g), pc, overlap, w.wall_contacts[k * n + i].spring);
    }
  }
  return e;
}

}  // namespace

void initialise(SphereWorld& world) {
  const int n = world.size();
  const int nm = static_cast<int>(world.materials.size());
  world.pair.assign(nm * nm, {});
  for (int a = 0; a < nm; ++a) {
    for (int b = 0; b < nm; ++b) {
      const contact::PairConstants c =
          contact::pair_constants(world.law.normal, world.law.friction, world.law.restitution,
                                  world.materials[a], world.materials[b]);
      world.pair[a * nm + b] = {.young_eff = c.young_eff,
                                .shear_eff = c.shear_eff,
                                .friction = c.friction,
                                .zeta = c.zeta};
    }
  }
  world.force = Eigen::Matrix3Xd::Zero(3, n);
  world.torque = Eigen::Matrix3Xd::Zero(3, n);
  double r_min = 1e300;
  for (double r : world.radius) r_min = std::min(r_min, r);
  // A skin of a fifth of the smallest radius: few rebuilds, few extra candidate pairs.
  world.skin = n > 0 ? 0.2 * r_min : 0;
  world.wall_contacts.assign(world.walls.size() * n, {});
  world.x_initial = world.x;
  // Contact output is per scene body: every sphere and wall must name its body.
  int bodies = 0;
  ASPERITY_CHECK(world.body.size() == static_cast<std::size_t>(n));
  for (int b : world.body) {
    ASPERITY_CHECK(b >= 0);
    bodies = std::max(bodies, b + 1);
  }
  for (const Wall& wall : world.walls) {
    ASPERITY_CHECK(wall.body >= 0);
    bodies = std::max(bodies, wall.body + 1);
  }
  world.contacts.reset(bodies);
  world.inv_mass.resize(n);
  world.inv_inertia.resize(n);
  for (int i = 0; i < n; ++i) {
    world.inv_mass[i] = 1.0 / world.mass[i];
    world.inv_inertia[i] = 1.0 / world.inertia[i];
  }
  world.v_end = world.v;
  rebuild_pairs(world);
  compute_forces(world, 0.0);
}

void step(SphereWorld& world, double dt) {
  const int n = world.size();
  const std::uint64_t t0 = ticks();
  const double moved = kick_drift(world, dt);
  const std::uint64_t t1 = ticks();
  // Verlet list: rebuilt once a sphere moved more than half the skin since it was built.
  if (moved > 0.25 * world.skin * world.skin) rebuild_pairs(world);
  const std::uint64_t t2 = ticks();
  compute_forces(world, dt);
  const std::uint64_t t3 = ticks();
  for (int i = 0; i < n; ++i) {
    if (world.fixed[i]) continue;
    world.v.col(i) += 0.5 * dt * (world.force.col(i) * world.inv_mass[i] + world.gravity);
    world.w.col(i) += 0.5 * dt * world.torque.col(i) * world.inv_inertia[i];
  }
  const std::uint64_t t4 = ticks();
  world.profile.integrate += (t1 - t0) + (t4 - t3);
  world.profile.broad_phase += t2 - t1;
  world.profile.contact += t3 - t2;
  world.time += dt;
  ++world.steps;
}

EnergyBalance energy(const SphereWorld& world) {
  EnergyBalance e;
  for (int i = 0; i < world.size(); ++i) {
    if (world.fixed[i]) continue;
    e.kinetic += 0.5 * world.mass[i] * world.v.col(i).squaredNorm() +
                 0.5 * world.inertia[i] * world.w.col(i).squaredNorm();
    e.gravity -= world.mass[i] * world.gravity.dot(world.x.col(i) - world.x_initial.col(i));
  }
  e.contact = contact_energy(world);
  e.dissipated = world.dissipated;
  return e;
}

std::size_t state_bytes(const SphereWorld& world) {
  const auto doubles = [](const auto& m) {
    return static_cast<std::size_t>(m.size()) * sizeof(double);
  };
  const auto held = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
  return doubles(world.x) + doubles(world.v) + doubles(world.w) + doubles(world.force) +
         doubles(world.torque) + doubles(world.v_end) + doubles(world.x_at_build) +
         doubles(world.x_initial) + held(world.radius) + held(world.mass) + held(world.inertia) +
         held(world.inv_mass) + held(world.inv_inertia) + held(world.material) + held(world.body) +
         held(world.fixed) + held(world.materials) + held(world.pair) + held(world.walls) +
         held(world.pairs) + held(world.history.spring[0]) + held(world.history.spring[1]) +
         held(world.history.spring[2]) + held(world.history.viscous) + held(world.laws) +
         held(world.wall_contacts) + doubles(world.contacts.force) +
         doubles(world.contacts.normal_force) + held(world.contacts.overlap);
}

}  // namespace asperity::dem
