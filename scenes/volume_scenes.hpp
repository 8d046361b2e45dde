// Rigid polyhedra under the volume laws, shared by the tests and the benchmarks: a faceted sphere
// (geodesic icosphere) and a cube, dropped on a fixed block or on each
// other; the smooth-sphere reference of the same law; and a loop that runs one impact.
#pragma once

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "scenes/fdem_scenes.hpp"
#include "solver/contact/volume_hertz.hpp"
#include "solver/fdem/fdem_world.hpp"
#include "solver/fdem/structured_mesh.hpp"
#include "solver/fdem/time_step.hpp"
#include "solver/geometry/geodesic_sphere.hpp"
#include "solver/geometry/tetrahedralize.hpp"

namespace asperity::fdem::volume_scenes {

inline Material stone() {
  return scenes::elastic("stone", 2500);
}

// Faceted sphere: radius r, geodesic frequency n (20 n² faces), centred at `centre`,
// tetrahedralized by TetGen keeping the facets (geometry/tetrahedralize.hpp): its tetrahedra are
// compact, so the broad phase pairs only those near the contact (a star of slivers from the
// centre would pair every cap tetrahedron with every other).
inline TetMesh faceted_sphere(double r, int n, const Vec3& centre) {
  SurfaceMesh s = geometry::geodesic_sphere(n);
  s.vertices *= r;
  TetMesh m = geometry::tetrahedralize(s);
  m.nodes.colwise() += centre;
  return m;
}

// Cube of side a, rotated by `rot` about its centre, centred at `centre`.
inline TetMesh cube(double a, const Mat3& rot, const Vec3& centre) {
  TetMesh m = box_mesh(Vec3::Constant(-a / 2), Vec3::Constant(a / 2), 1, 1, 1);
  m.nodes = (rot * m.nodes).colwise() + centre;
  return m;
}

// Rotations that put a cube's vertex, edge or face lowest (towards −z).
inline Mat3 vertex_down() {
  return Quat::FromTwoVectors(Vec3(-1, -1, -1).normalized(), Vec3(0, 0, -1)).toRotationMatrix();
}
inline Mat3 edge_down() {
  return Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitX()).toRotationMatrix();
}

using scenes::block;

// Lowest z of a mesh.
inline double lowest(const TetMesh& m) {
  return m.nodes.row(2).minCoeff();
}

using scenes::Impact;

// The impact at dt = safety × the predicted step (fdem_scenes.hpp, step_impact). The duration
// counts whole steps with a force plus the fractions before the first and after the last one
// found by linear interpolation of the overlap's mean depth V/|S| (World::contacts.overlap),
// which is linear in time at both ends. The recorded body is body 0.
inline Impact run_impact(World& w, double t_max, double safety = 0.01) {
  long touching_steps = 0;
  double t_first = 0, d_first = 0, d_second = 0, d_prev = 0, d_last = 0, d_before_last = 0;
  Impact out = scenes::step_impact(w, t_max, safety, [&](const Impact&) {
    const double d = w.contacts.overlap[0];
    if (touching_steps == 0) t_first = w.time, d_first = d;
    if (touching_steps == 1) d_second = d;
    d_before_last = d_prev, d_last = d;
    d_prev = d;
    ++touching_steps;
  });
  if (touching_steps >= 3) {
    const double start = t_first - out.dt * d_first / (d_second - d_first);
    const double end = t_first + out.dt * static_cast<double>(touching_steps - 1) +
                       out.dt * d_last / (d_before_last - d_last);
    out.duration = end - start;
  }
  return out;
}

// The same law on a smooth sphere pressed δ into a plane (or a lens of two spheres), integrated
// in δ alone: m δ'' = −W'(V(δ)) |S(δ)|, by velocity Verlet at 1e-5 of the Hertz time.
// Plane: V = π δ² (R − δ/3), |S| = π (2Rδ − δ²). Two equal spheres of radius R approaching by
// δ: two caps of height δ/2, V = 2 π (δ/2)² (R − δ/6), |S| = π (R δ − δ²/4).
struct SmoothImpact {
  double peak_force = 0, duration = 0;
};
inline SmoothImpact smooth_sphere_impact(double r, double mass, double v, double e_star,
                                         double r_star, bool two_spheres) {
  const double c = contact::volume_hertz_coefficient(e_star, r_star);
  auto force = [&](double d) {
    if (d <= 0) return 0.0;
    const double vol = two_spheres ? 0.5 * std::numbers::pi * d * d * (r - d / 6)
                                   : std::numbers::pi * d * d * (r - d / 3);
    const double s = two_spheres ? std::numbers::pi * (r * d - d * d / 4)
                                 : std::numbers::pi * (2 * r * d - d * d);
    return contact::volume_hertz(vol, c).slope * s;
  };
  const double d_hertz = std::pow(15 * mass * v * v / (16 * e_star * std::sqrt(r_star)), 0.4);
  const double dt = 1e-5 * 2.94 * d_hertz / v;
  double d = 0, u = v, f = 0, t = 0;
  SmoothImpact out;
  do {
    u -= 0.5 * dt * f / mass;
    d += dt * u;
    f = force(d);
    u -= 0.5 * dt * f / mass;
    t += dt;
    out.peak_force = std::max(out.peak_force, f);
  } while (d > 0);
  // The last step crossed δ = 0: place the end by linear interpolation.
  out.duration = t + d / u;
  return out;
}

}  // namespace asperity::fdem::volume_scenes
