// Coulomb friction at the potential contact (contact/potential_friction.hpp,
// fdem/potential_contact.cpp): a box sliding on a fixed block against the rigid-body solutions of
// Coulomb's law.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "scenes/fdem_scenes.hpp"

namespace asperity::fdem {
namespace {

constexpr double kG = 9.81;      // m/s²
constexpr double kSide = 0.1;    // m, the sliding box
constexpr double kBlockH = 0.1;  // m, the fixed block's depth (one cell)

// Depth at which the penalty carries the box's weight component w_n (N), for a box of one cell
// (side L) face-on on a block of one cell (depth H): every face of a Kuhn cell belongs to a
// tetrahedron of volume cell/6, so the sub-tetrahedron height under the box's bottom is L/4 and
// above the block's top H/4, and the overlap layer A·d pushes with p A d (4/L + 4/H)
// (Munjiza 2004, eq. 2.38, ∇φ = 1/height in each sub-tetrahedron). Starting there, the box does
// not bounce on the penalty layer, so the normal force is the weight from the first step.
double resting_depth(double penalty, double w_n, double cell_height) {
  return w_n / (penalty * kSide * kSide * (4 / cell_height + 4 / kBlockH));
}

struct Slide {
  WorldDef def;
  double depth = 0;  // the box's starting overlap, m
};

// A box (nx × nx × 1 cells, side kSide) resting on a fixed block whose top is z = 0, moving along
// x at v0, under gravity g (m/s², tilted by theta about y so that x points downhill), friction μ.
Slide box_on_block(BodyKind kind, int nx, double mu, double v0, double theta) {
  Slide s;
  Material m = scenes::rubbery();
  m.friction = mu;
  s.def.contact.friction = mu;
  s.def.gravity = kG * Vec3(std::sin(theta), 0, -std::cos(theta));
  const double penalty = s.def.contact.alpha * m.young;
  s.depth = resting_depth(penalty, m.density * std::pow(kSide, 3) * kG * std::cos(theta), kSide);
  s.def.bodies.push_back({.name = "box",
                          .kind = kind,
                          .mesh = box_mesh(Vec3(0, -kSide / 2, -s.depth),
                                           Vec3(kSide, kSide / 2, kSide - s.depth), nx, nx, 1),
                          .material = m,
                          .velocity = Vec3(v0, 0, 0)});
  s.def.bodies.push_back({.name = "block",
                          .kind = BodyKind::fixed,
                          .mesh = box_mesh(Vec3(-0.2, -0.2, -kBlockH), Vec3(0.6, 0.2, 0), 1, 1, 1),
                          .material = m});
  return s;
}

struct Track {
  double half_time = -1;     // s, first step at which v_x ≤ v_x(0)/2 (−1: not yet)
  double stop_time = -1;     // s, first step at which v_x ≤ 0 (−1: still moving)
  double stop_distance = 0;  // m, travel of the centre until then
  double distance = 0;       // m, travel of the centre at the end
  double v_end = 0;          // m/s, v_x at the end
  double max_slip = 0;       // m, largest |x − x₀| of the centre of the base
  double max_depth = 0;      // m, deepest penetration of any of its pairs
  double time = 0;           // s, the world's time at the end
};

// Mean x of the box's lowest nodes (the centre of its base): rocking on the penalty layer turns
// the box about its base, which moves its centre of mass but hardly its base.
double base_x(const World& w) {
  const Body& b = w.bodies[0];
  double z_min = 1e300, sum = 0;
  int n = 0;
  for (int i = b.node_begin; i < b.node_end; ++i) z_min = std::min(z_min, w.x_initial(2, i));
  for (int i = b.node_begin; i < b.node_end; ++i) {
    if (w.x_initial(2, i) < z_min + 1e-9) sum += w.x(0, i), ++n;
  }
  return sum / n;
}

// Steps at half the predicted critical step for t_end (or until it stops when stop_at_rest).
Track run(World& w, double t_end, bool stop_at_rest) {
  Track t;
  const double dt = 0.5 * critical_step(w).critical;
  w.want_energy = false;
  const double x0 = body_centre(w, 0).x(), b0 = base_x(w), v0 = body_velocity(w, 0).x();
  while (w.time < t_end && w.failure.empty()) {
    step(w, dt);
    const double dx = body_centre(w, 0).x() - x0;
    t.max_slip = std::max(t.max_slip, std::abs(base_x(w) - b0));
    t.max_depth = std::max(t.max_depth, w.contacts.overlap[0]);
    if (t.half_time < 0 && body_velocity(w, 0).x() <= 0.5 * v0) t.half_time = w.time;
    if (t.stop_time < 0 && body_velocity(w, 0).x() <= 0) {
      t.stop_time = w.time;
      t.stop_distance = dx;
      if (stop_at_rest) break;
    }
  }
  t.distance = body_centre(w, 0).x() - x0;
  t.v_end = body_velocity(w, 0).x();
  t.time = w.time;
  return t;
}

// box_on_block's box (its kind and cells, μ, v0 along x, gravity tilted by θ) run as `run` does;
// the run must end without a failure.
Track slide(BodyKind kind, int cells, double mu, double v0, double theta, double t_end,
            bool stop_at_rest) {
  Slide s = box_on_block(kind, cells, mu, v0, theta);
  World w = make_world(s.def);
  const Track t = run(w, t_end, stop_at_rest);
  EXPECT_TRUE(w.failure.empty()) << w.failure;
  return t;
}

// A rigid box sliding at v0 on a level block decelerates at μg: it stops after t = v0/(μg) and
// d = v0²/(2μg). 1 %: the friction acts from the first step (the tangential spring reaches the
// cap after a slip of μ·depth, ~1e-6 of d), the normal force is the weight to within the small
// rocking of the box on its penalty layer (friction at the base tips it forward, shifting the
// pressure, not its total), and the step error of v is μg·dt, ~1e-4 of v0.
TEST(Friction, RigidBoxSlidingOnLevelBlockStopsAfterCoulombDistance) {
  const double mu = 0.3, v0 = 1.0;
  const Track t = slide(BodyKind::rigid, 1, mu, v0, 0, 1.0, true);
  ASSERT_GT(t.stop_time, 0) << "still sliding at t = 1 s";
  const double t_stop = v0 / (mu * kG), d_stop = v0 * v0 / (2 * mu * kG);
  EXPECT_NEAR(t.stop_time / t_stop, 1.0, 0.01) << t.stop_time << " s vs " << t_stop << " s";
  EXPECT_NEAR(t.stop_distance / d_stop, 1.0, 0.01) << t.stop_distance << " m vs " << d_stop;
}

// Gravity tilted by θ (the block an incline): a box at rest sticks when tan θ < μ. Its base may
// move only by the tangential penalty springs' elastic stretch: each pair's spring has the secant
// normal stiffness F_n/depth (depth its deepest point), so the static stretch is at most
// tan θ · depth_max and an undamped start overshoots it by at most 2×; 1.5× more for the
// pressure centre moving as the box rocks. That is ~1e-5 of the free slide in the same time.
TEST(Friction, RigidBoxOnInclineSticksBelowFrictionAngle) {
  const double mu = 0.5, theta = 20 * std::numbers::pi / 180, t_end = 0.2;
  ASSERT_LT(std::tan(theta), mu);
  const Track t = slide(BodyKind::rigid, 1, mu, 0, theta, t_end, false);
  ASSERT_GT(t.max_depth, 0);
  EXPECT_LT(t.max_slip, 1.5 * 2 * t.max_depth * std::tan(theta))
      << "free slide would be " << 0.5 * kG * std::sin(theta) * t_end * t_end << " m";
}

// Above the friction angle it slides with a = g (sin θ − μ cos θ): after t, v = a t and
// x = a t²/2. 1 %, for the reasons of the level test.
TEST(Friction, RigidBoxOnInclineSlidesAboveFrictionAngle) {
  const double mu = 0.2, theta = 30 * std::numbers::pi / 180, t_end = 0.2;
  ASSERT_GT(std::tan(theta), mu);
  const Track t = slide(BodyKind::rigid, 1, mu, 0, theta, t_end, false);
  const double a = kG * (std::sin(theta) - mu * std::cos(theta));
  EXPECT_NEAR(t.v_end / (a * t.time), 1.0, 0.01) << "a = " << t.v_end / t.time << " vs " << a;
  EXPECT_NEAR(t.distance / (0.5 * a * t.time * t.time), 1.0, 0.01);
}

// A deformable box (2 × 2 × 1 cells, neo-Hookean) sliding on the level block decelerates at μg
// too: Coulomb's law on every contact pair sums to μ times the total normal force, which is the
// weight on average. 3 %: the body vibrates (undamped) on its penalty layer and in its own
// modes, so the pressure moves between pairs, and a pair whose normal force drops faster than
// its spring can follow sticks for a step. The deceleration is read where the speed has halved
// (v0/2 = μ g t½) and the stop by the distance travelled: both integrate the friction over the
// slide. The stop time itself is not asserted: near rest the centre's v_x carries the body's
// vibration, so its first crossing of zero lags by a fraction of a vibration period (1.8–3 %
// here, depending on the step).
TEST(Friction, DeformableBoxSlidingOnLevelBlockStopsAfterCoulombDistance) {
  const double mu = 0.3, v0 = 1.0;
  const Track t = slide(BodyKind::deformable, 2, mu, v0, 0, 1.0, true);
  ASSERT_GT(t.stop_time, 0) << "still sliding at t = 1 s";
  const double t_stop = v0 / (mu * kG), d_stop = v0 * v0 / (2 * mu * kG);
  EXPECT_NEAR(t.half_time / (0.5 * t_stop), 1.0, 0.03)
      << t.half_time << " s vs " << 0.5 * t_stop << " s";
  EXPECT_NEAR(t.stop_distance / d_stop, 1.0, 0.03) << t.stop_distance << " m vs " << d_stop;
}

}  // namespace
}  // namespace asperity::fdem
