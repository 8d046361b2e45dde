// The Hertz–Mindlin law over a batch of contacts in columns (mindlin_columns.hpp), in copies for
// the instruction sets of x86-64 chosen at run time.
#include "solver/dem/mindlin_columns.hpp"

#include <cmath>
#include <initializer_list>

namespace asperity::dem {
namespace {

inline double dot3(double ax, double ay, double az, double bx, double by, double bz) {
  return (ax * bx + ay * by) + az * bz;
}

[[gnu::always_inline]] inline void columns(MindlinColumns& __restrict b, std::size_t t, double dt,
                                           double* __restrict sx, double* __restrict sy,
                                           double* __restrict sz, double* __restrict viscous) {
  // hertz_contact<true> written out in scalars over the columns. Each line is the operation the
  // Eigen expression it replaces performs, in the same order (a 3-vector's dot product and squared
  // norm are (x x' + y y') + z z', as Eigen's two-lane reduction sums them; a cross product is
  // Eigen's (a_y b_z − a_z b_y, …)), no multiply-add is fused (-ffp-contract=off for this file),
  // and both sides of the Coulomb test are computed and one chosen, so every contact gets the bits
  // it gets computed whole. The formulas: contact::hertz_normal,
  // contact::rotate_into_tangent_plane, contact::tangential_spring (Hertz–Mindlin:
  // contact::hertz_mindlin) and outcome(). The history (sx, sy, sz: the spring, N; viscous, N)
  // is read and written in place: contact m's last step's on entry, this step's on return.
  for (std::size_t m = 0; m < t; ++m) {
    // The normal, one quotient (n = d · (1/|d|)).
    const double inv = 1.0 / b.dist[m];
    const double nx = b.d[0][m] * inv, ny = b.d[1][m] * inv, nz = b.d[2][m] * inv;
    const double overlap = b.overlap[m];
    b.ratio[m] = overlap * b.inv_min_radius[m];
    // Contact arms and the relative velocity at the contact point.
    const double a1 = -(b.ri[m] - 0.5 * overlap), a2 = b.rj[m] - 0.5 * overlap;
    const double a1x = a1 * nx, a1y = a1 * ny, a1z = a1 * nz;
    const double a2x = a2 * nx, a2y = a2 * ny, a2z = a2 * nz;
    const double wix = b.wi[0][m], wiy = b.wi[1][m], wiz = b.wi[2][m];
    const double wjx = b.wj[0][m], wjy = b.wj[1][m], wjz = b.wj[2][m];
    const double vx =
        (b.vi[0][m] + (wiy * a1z - wiz * a1y)) - (b.vj[0][m] + (wjy * a2z - wjz * a2y));
    const double vy =
        (b.vi[1][m] + (wiz * a1x - wix * a1z)) - (b.vj[1][m] + (wjz * a2x - wjx * a2z));
    const double vz =
        (b.vi[2][m] + (wix * a1y - wiy * a1x)) - (b.vj[2][m] + (wjx * a2y - wjy * a2x));
    const double rate_end = -dot3(b.dv_end[0][m], b.dv_end[1][m], b.dv_end[2][m], nx, ny, nz);
    const double vn = dot3(vx, vy, vz, nx, ny, nz);
    const double rate = -vn;
    // Hertz's normal force with Tsuji's dashpot (contact::hertz_normal).
    const double sqrt_d = std::sqrt(overlap), fourth_d = std::sqrt(sqrt_d);
    const double elastic = b.k[m] * overlap * sqrt_d;
    const double damping = b.damping[m] * fourth_d * rate_end;
    const double sum = elastic + damping;
    const double fn = 0.0 < sum ? sum : 0.0;  // std::max(0.0, sum)
    // Last step's spring rotated into the tangent plane (contact::rotate_into_tangent_plane).
    const double sx0 = sx[m], sy0 = sy[m], sz0 = sz[m];
    const double sn = dot3(sx0, sy0, sz0, nx, ny, nz);
    double rx = sx0 - sn * nx, ry = sy0 - sn * ny, rz = sz0 - sn * nz;
    const double ss = dot3(rx, ry, rz, rx, ry, rz);
    const double scale = std::sqrt(dot3(sx0, sy0, sz0, sx0, sy0, sz0) / ss);
    rx = ss > 0 ? rx * scale : rx;
    ry = ss > 0 ? ry * scale : ry;
    rz = ss > 0 ? rz * scale : rz;
    // The tangential spring with its Coulomb cap (contact::tangential_spring).
    const double slx = vx - vn * nx, sly = vy - vn * ny, slz = vz - vn * nz;
    const double kt = b.shear[m] * sqrt_d, ct = b.shear_damping[m] * fourth_d;
    const double kdt = kt * dt, mct = -ct;
    const double trx = rx - kdt * slx, try_ = ry - kdt * sly, trz = rz - kdt * slz;
    const double fdx = mct * slx, fdy = mct * sly, fdz = mct * slz;
    const double tfx = trx + fdx, tfy = try_ + fdy, tfz = trz + fdz;
    const double cap = b.friction[m] * fn;
    const double tf2 = dot3(tfx, tfy, tfz, tfx, tfy, tfz);
    const bool sliding = tf2 > cap * cap;
    // Sliding: μ F_n along the trial force, carried by the spring; the work of the slip.
    const double total = std::sqrt(tf2);
    const double share = cap / total;
    const double excess = std::sqrt(dot3(trx, try_, trz, trx, try_, trz)) - cap;
    const double slid = cap * (0.0 < excess ? excess : 0.0) / kt;
    const double slide_x = total > 0 ? share * tfx : 0.0;
    const double slide_y = total > 0 ? share * tfy : 0.0;
    const double slide_z = total > 0 ? share * tfz : 0.0;
    // Sticking: spring plus dashpot; the dashpot's work.
    const double stick = -dot3(fdx, fdy, fdz, slx, sly, slz) * dt;
    const double spx = sliding ? slide_x : trx, spy = sliding ? slide_y : try_,
                 spz = sliding ? slide_z : trz;
    const double ftx = sliding ? slide_x : tfx, fty = sliding ? slide_y : tfy,
                 ftz = sliding ? slide_z : tfz;
    const double tangential_work = sliding ? (kt > 0 ? slid : 0.0) : stick;
    // The contact's outcome (outcome()): total force, normal part, work of the normal dashpot.
    const double nfx = fn * nx, nfy = fn * ny, nfz = fn * nz;
    const double viscous_now = fn - elastic;
    b.dissipated[m] = 0.5 * (viscous[m] + viscous_now) * rate * dt + tangential_work;
    viscous[m] = viscous_now;
    sx[m] = spx;
    sy[m] = spy;
    sz[m] = spz;
    const double fx = nfx + ftx, fy = nfy + fty, fz = nfz + ftz;
    b.normal_force[0][m] = nfx;
    b.normal_force[1][m] = nfy;
    b.normal_force[2][m] = nfz;
    b.force[0][m] = fx;
    b.force[1][m] = fy;
    b.force[2][m] = fz;
    b.torque_i[0][m] = a1y * fz - a1z * fy;
    b.torque_i[1][m] = a1z * fx - a1x * fz;
    b.torque_i[2][m] = a1x * fy - a1y * fx;
    b.torque_j[0][m] = a2y * fz - a2z * fy;
    b.torque_j[1][m] = a2z * fx - a2x * fz;
    b.torque_j[2][m] = a2x * fy - a2y * fx;
  }
}

void columns_baseline(MindlinColumns& __restrict b, std::size_t t, double dt, double* __restrict sx,
                      double* __restrict sy, double* __restrict sz, double* __restrict viscous) {
  columns(b, t, dt, sx, sy, sz, viscous);
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define ASPERITY_MINDLIN_COPIES 1
// GCC 12 vectorises every copy: v4 8 contacts per instruction (AVX-512, the selects as masks), v3
// 4 (AVX2, the selects as blends), the baseline 2 (SSE2). The v3 and baseline copies only since
// this file is compiled without trapping math (solver/CMakeLists.txt): BM_Packing10k mindlin with
// the v3 copy forced, 1.96 -> 1.35 ms per step (0.683x, 8 interleaved pairs; BM_MindlinColumns
// copy:1, the law alone, 2.7x).
[[gnu::target("arch=x86-64-v4")]] void columns_v4(MindlinColumns& __restrict b, std::size_t t,
                                                  double dt, double* __restrict sx,
                                                  double* __restrict sy, double* __restrict sz,
                                                  double* __restrict viscous) {
  columns(b, t, dt, sx, sy, sz, viscous);
}

[[gnu::target("arch=x86-64-v3")]] void columns_v3(MindlinColumns& __restrict b, std::size_t t,
                                                  double dt, double* __restrict sx,
                                                  double* __restrict sy, double* __restrict sz,
                                                  double* __restrict viscous) {
  columns(b, t, dt, sx, sy, sz, viscous);
}
#endif

}  // namespace

MindlinColumnsFn mindlin_columns_copy(MindlinCopy copy) {
  switch (copy) {
    case MindlinCopy::baseline:
      return columns_baseline;
#ifdef ASPERITY_MINDLIN_COPIES
    case MindlinCopy::x86_64_v3:
      __builtin_cpu_init();
      return __builtin_cpu_supports("x86-64-v3") ? columns_v3 : nullptr;
    case MindlinCopy::x86_64_v4:
      __builtin_cpu_init();
      return __builtin_cpu_supports("x86-64-v4") ? columns_v4 : nullptr;
#endif
    default:
      return nullptr;
  }
}

MindlinColumnsFn mindlin_columns() {
  static const MindlinColumnsFn widest = [] {
    for (MindlinCopy copy : {MindlinCopy::x86_64_v4, MindlinCopy::x86_64_v3}) {
      if (MindlinColumnsFn f = mindlin_columns_copy(copy)) return f;
    }
    return mindlin_columns_copy(MindlinCopy::baseline);
  }();
  return widest;
}

}  // namespace asperity::dem
