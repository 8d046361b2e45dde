// The Hertz convergence scene (issue 11) of test_hertz_convergence.cpp: a deformable sphere
// meshed through the geometry pipeline with an element size graded towards its strike point,
// striking a fixed block, and the Hertz impact it must converge to.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "scenes/fdem_scenes.hpp"
#include "solver/geometry/element_size.hpp"
#include "solver/geometry/refined_sphere.hpp"
#include "solver/geometry/tetrahedralize.hpp"

namespace asperity::fdem::hertz {

inline constexpr double kRadius = 0.1;  // m
// 0.2 m/s on the rubbery material: Hertz approach δ = 1.15 mm, contact radius a = √(Rδ) =
// 10.7 mm, a/R = 0.107.
inline constexpr double kSpeed = 0.2;  // m/s
// The geometry: a geodesic sphere of frequency 8 (edge ≈ 14 mm), bisected near the strike
// point with every new vertex put back on the sphere, down to 2.5 mm edges within 30 mm of it:
// there the chord error (sagitta) e²/(8R) = 7.8 µm is 0.7 % of the Hertz approach, spread over
// the ~60 facets of the contact patch. The facets elsewhere never touch; the Hertz reference
// takes the mass of the meshed volume, so their volume defect (−0.5 %) is not an error.
inline constexpr double kGeometryEdge = 0.0025;  // m, near the strike point
inline constexpr double kGeometryPatch = 0.03;   // m, radius of that fine patch
inline constexpr double kGrowth = 0.3;           // element size growth away from the contact

// Sphere of radius R centred at the origin whose strike point is (0, 0, −R), with facets of
// `edge` within `patch` of it (the a/R series scales both with the contact radius, so the
// sagitta stays 0.7 % of the approach and the patch holds the same ~60 facets).
inline SurfaceMesh sphere_surface(double r = kRadius, double edge = kGeometryEdge,
                                  double patch = kGeometryPatch) {
  return geometry::refined_sphere(8, r, edge, patch, Vec3(0, 0, -r));
}

// Element size h at the strike point, constant within 2 contact radii of it, growing at
// `growth` beyond up to `far` (graded), or h everywhere the geometry allows (uniform: growth 0).
// The whole-field refinement of the convergence gate scales all three together (s·h, s·growth,
// s·far), so every element shrinks by s: the interior far from the contact carries a quarter of
// the sphere's compliance (a point load's displacement falls as 1/r) and must refine too.
inline geometry::ElementSize element_size(double h, bool graded, double r = kRadius,
                                          double growth = kGrowth, double far = 0.025,
                                          double focus_radius = 0.02) {
  if (!graded) return {.size = h};
  return {.size = h,
          .focus = Vec3(0, 0, -r),
          .focus_radius = focus_radius,
          .growth = growth,
          .far = far};
}

inline TetMesh sphere_mesh(double h, bool graded, double radius_edge_ratio = 1.5,
                           double growth = kGrowth, double far = 0.025) {
  geometry::TetOptions o;
  o.radius_edge_ratio = radius_edge_ratio;
  o.element_size = element_size(h, graded, kRadius, growth, far);
  return geometry::tetrahedralize(sphere_surface(), o);
}

inline double mesh_volume(const TetMesh& m) {
  double v = 0;
  for (Eigen::Index k = 0; k < m.tets.cols(); ++k) {
    const Vec3 a = m.nodes.col(m.tets(0, k));
    v += (Vec3(m.nodes.col(m.tets(1, k))) - a)
             .cross(Vec3(m.nodes.col(m.tets(2, k))) - a)
             .dot(Vec3(m.nodes.col(m.tets(3, k))) - a) /
         6.0;
  }
  return v;
}

// Hertz impact of two bodies (Johnson 1985, §11.4): reduced mass m*, radius R*, modulus E*,
// approach speed v: δ_max = (15 m* v² / (16 E* √R*))^{2/5}, F_max = 4/3 E* √R* δ_max^{3/2},
// duration 2.9432 δ_max / v.
inline scenes::Hertz hertz_impact(double m_star, double r_star, double e_star, double v) {
  const double d = std::pow(15 * m_star * v * v / (16 * e_star * std::sqrt(r_star)), 0.4);
  return {.overlap = d,
          .force = 4.0 / 3.0 * e_star * std::sqrt(r_star) * std::pow(d, 1.5),
          .duration = 2.9432 * d / v};
}

// The meshed sphere `ball` (strike point at (0, 0, −R)) `gap` above a fixed block, moving down.
inline WorldDef sphere_on_block(const TetMesh& ball, const Material& m, double alpha = 10,
                                double speed = kSpeed, double gap = 2e-4) {
  WorldDef def;
  def.bodies.push_back({.name = "ball",
                        .kind = BodyKind::deformable,
                        .mesh = scenes::translated(ball, Vec3(0, 0, kRadius + gap)),
                        .material = m,
                        .velocity = Vec3(0, 0, -speed)});
  def.bodies.push_back({.name = "block",
                        .kind = BodyKind::fixed,
                        .mesh = box_mesh(Vec3(-2 * kRadius, -2 * kRadius, -kRadius),
                                         Vec3(2 * kRadius, 2 * kRadius, 0), 1, 1, 1),
                        .material = m});
  def.contact.alpha = alpha;
  return def;
}
inline scenes::Hertz sphere_on_block_hertz(const TetMesh& ball, const Material& m,
                                           double speed = kSpeed) {
  return hertz_impact(m.density * mesh_volume(ball), kRadius, m.young / (1 - m.poisson * m.poisson),
                      speed);
}

}  // namespace asperity::fdem::hertz
