// Hertz by refinement: a deformable ball striking a fixed block at low speed approaches the Hertz
// sphere-on-rigid-plane peak force and contact duration as the mesh is refined.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>

#include "scenes/fdem_scenes.hpp"

namespace asperity::fdem {
namespace {

// v = 0.2 m/s gives a/R = 0.11 and a peak strain of about 1 %: Hertz's own premise (small
// strain, a ≪ R). At 1 m/s (a/R = 0.2) the measured peak force stays 12–20 % above Hertz and does
// not converge towards it, since finite strain and the penalty's high-frequency ringing both
// add to the peak. The gate is the issue's: within 10 % at the finest mesh here (~10 s), and the
// force error must fall with every refinement (refinement, not luck). n = 4 is left out: its
// contact radius is a fraction of one element and its error (+4 % F, +9 % T) is a cancellation.
TEST(HertzRefinement, PeakForceAndDurationApproachHertz) {
  const double r = 0.1, v = 0.2;
  const Material m = scenes::rubbery();
  const scenes::Hertz h = scenes::hertz_sphere_on_rigid_plane(r, v, m);
  std::printf("Hertz: peak %.4g N, duration %.4g s, overlap %.4g m\n", h.force, h.duration,
              h.overlap);
  std::printf("%4s %7s %9s %9s %8s %8s %8s\n", "n", "tets", "h_m", "cpu_s", "err_F", "err_T",
              "drift");
  double err_f_last = 0, err_t_last = 0, err_f_previous = 1e300;
  for (int n : {6, 8, 10}) {
    const auto t0 = std::chrono::steady_clock::now();
    World w = make_world(scenes::ball_on_block(r, n, v, BodyKind::deformable, m, 0.001));
    const scenes::Impact im = scenes::run_impact(w, 0.1);
    const double cpu = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_TRUE(w.failure.empty()) << w.failure;
    err_f_last = im.peak_force / h.force - 1;
    err_t_last = im.duration / h.duration - 1;
    EXPECT_LT(std::abs(err_f_last), err_f_previous) << "n = " << n;
    err_f_previous = std::abs(err_f_last);
    std::printf("%4d %7d %9.4f %9.3f %+8.3f %+8.3f %8.4f\n", n, w.elements[0].size(), 2 * r / n,
                cpu, err_f_last, err_t_last, im.drift);
  }
  EXPECT_LT(std::abs(err_f_last), 0.10);
  EXPECT_LT(std::abs(err_t_last), 0.10);
}

}  // namespace
}  // namespace asperity::fdem
