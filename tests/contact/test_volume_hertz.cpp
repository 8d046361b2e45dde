// volume-hertz's tangential stiffness (contact/volume_hertz.hpp): Mindlin's on a sphere, Mindlin's
// ratio to the normal stiffness on an edge, three times it on a face.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "solver/contact/volume_hertz.hpp"
#include "solver/core/material.hpp"

using namespace asperity;
using namespace asperity::contact;

namespace {

const Material kStone{.name = "stone", .density = 2650, .young = 5e10, .poisson = 0.25};
const double kE = effective_young(kStone, kStone), kG = effective_shear(kStone, kStone);
constexpr double kR = 0.01;  // m
const double kC = volume_hertz_coefficient(kE, kR);

// |F_n| of volume-hertz for an overlap V with cross-section |S|.
double normal_force(double v, double s) {
  return volume_hertz(v, kC).slope * s;
}

}  // namespace

// Sphere on a plane, exact cap: V = πδ²(R − δ/3), |S| = π(2Rδ − δ²). k_t against Mindlin's
// 8 G* √(Rδ): the law departs from Hertz at O(δ/R), so the error must fall in proportion to δ
// (each decade of δ by more than 8×) and be below 1 % at δ = 1e-3 R.
TEST(VolumeHertzTangentStiffness, SphereIsMindlin) {
  double prev = 1;
  for (const double d : {1e-2 * kR, 1e-3 * kR, 1e-4 * kR}) {
    const double v = std::numbers::pi * d * d * (kR - d / 3);
    const double s = std::numbers::pi * (2 * kR * d - d * d);
    const double kt = volume_hertz_tangent_stiffness(normal_force(v, s), s, v, kG, kE);
    const double err = std::abs(kt / (8 * kG * std::sqrt(kR * d)) - 1);
    EXPECT_LT(err, prev / 8) << "δ/R = " << d / kR;
    prev = err;
  }
  EXPECT_LT(prev, 1e-3);
}

// A cube's edge (a 90° wedge of length L pressed δ: V = Lδ², |S| = 2Lδ) and face (area A:
// V = Aδ, |S| = A). k_t over the tangent normal stiffness dF/dδ (central difference, 1e-6
// relative step: truncation 1e-12, round-off 1e-10): the edge gets Mindlin's 4G*/E*, the face
// three times it; both exact in the law, asserted to 1e-6.
TEST(VolumeHertzTangentStiffness, EdgeHasMindlinsRatioFaceThreeTimes) {
  const double l = 0.02, a = 4e-4, d = 1e-6;
  auto edge = [&](double x) { return normal_force(l * x * x, 2 * l * x); };
  auto face = [&](double x) { return normal_force(a * x, a); };
  const double h = 1e-6 * d;
  const double kn_edge = (edge(d + h) - edge(d - h)) / (2 * h);
  const double kn_face = (face(d + h) - face(d - h)) / (2 * h);
  const double kt_edge = volume_hertz_tangent_stiffness(edge(d), 2 * l * d, l * d * d, kG, kE);
  const double kt_face = volume_hertz_tangent_stiffness(face(d), a, a * d, kG, kE);
  EXPECT_NEAR(kt_edge / kn_edge / (4 * kG / kE), 1.0, 1e-6);
  EXPECT_NEAR(kt_face / kn_face / (12 * kG / kE), 1.0, 1e-6);
  // Like materials: Mindlin's ratio is 2(1 − ν)/(2 − ν).
  EXPECT_NEAR(4 * kG / kE, 2 * (1 - kStone.poisson) / (2 - kStone.poisson), 1e-12);
}
