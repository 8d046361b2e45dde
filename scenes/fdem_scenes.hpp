// FEM/DEM scenes shared by the tests and the benchmarks: a ball (cube-mapped tetrahedral mesh)
// dropped on a fixed block, and two balls head-on; plus a loop that runs one impact and measures
// it.
#pragma once

#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include "solver/fdem/fdem_world.hpp"
#include "solver/fdem/structured_mesh.hpp"
#include "solver/fdem/time_step.hpp"

namespace asperity::fdem::scenes {

// A frictionless elastic material of E = 10 MPa, ν = 0.3: soft enough that a contact spans
// many steps at the critical one.
inline Material elastic(std::string name, double density) {
  return {.name = std::move(name),
          .density = density,
          .young = 1e7,
          .poisson = 0.3,
          .friction = 0,
          .restitution = 1};
}
inline Material rubbery() {
  return elastic("soft", 1000);
}

inline TetMesh translated(TetMesh m, const Vec3& d) {
  m.nodes.colwise() += d;
  return m;
}

// Mirror image through the plane x = 0 (node order swapped to keep volumes positive).
inline TetMesh mirrored_x(TetMesh m) {
  m.nodes.row(0) *= -1;
  m.tets.row(1).swap(m.tets.row(2));
  m.surface.row(1).swap(m.surface.row(2));
  return m;
}

// Mirror image through z = 0 (node order swapped to keep volumes positive).
inline TetMesh mirrored_z(TetMesh m) {
  m.nodes.row(2) *= -1;
  m.tets.row(1).swap(m.tets.row(2));
  m.surface.row(1).swap(m.surface.row(2));
  return m;
}

// Two deformable bodies head-on: "upper", the mesh (above z = 0) moving down at `speed`, and
// "lower", its mirror image through z = 0 moving up at `speed`. Total momentum zero; the mid-plane
// is a plane of symmetry, so each body sees a frictionless rigid plane at `speed`.
inline WorldDef mirrored_pair(const TetMesh& upper, const Material& m, double speed) {
  WorldDef def;
  def.bodies.push_back({.name = "upper",
                        .kind = BodyKind::deformable,
                        .mesh = upper,
                        .material = m,
                        .velocity = Vec3(0, 0, -speed)});
  def.bodies.push_back({.name = "lower",
                        .kind = BodyKind::deformable,
                        .mesh = mirrored_z(upper),
                        .material = m,
                        .velocity = Vec3(0, 0, speed)});
  return def;
}

// A fixed block whose top is z = 0, wide enough for anything of size `size` near the origin.
inline BodyDef block(double size, const Material& m) {
  return {.name = "block",
          .kind = BodyKind::fixed,
          .mesh = box_mesh(Vec3(-2 * size, -2 * size, -size), Vec3(2 * size, 2 * size, 0), 1, 1, 1),
          .material = m};
}

// A ball of radius r (n cells per cube side) just above a fixed block whose top is z = 0,
// moving down at speed v. `gap` is the initial clearance, m.
inline WorldDef ball_on_block(double r, int n, double v, BodyKind kind, const Material& mat,
                              double gap) {
  WorldDef def;
  def.bodies.push_back({.name = "ball",
                        .kind = kind,
                        .mesh = translated(ball_mesh(r, n), Vec3(0, 0, r + gap)),
                        .material = mat,
                        .velocity = Vec3(0, 0, -v)});
  def.bodies.push_back(block(r, mat));
  return def;
}

// Hertz sphere on a rigid plane (Johnson 1985, §11.1): δ_max = (15 m v² / (16 E* √R))^{2/5},
// F_max = 4/3 E* √R δ_max^{3/2}, duration 2.9432 δ_max / v, E* = E/(1 − ν²).
struct Hertz {
  double overlap, force, duration;
};
inline Hertz hertz_sphere_on_rigid_plane(double r, double v, const Material& m) {
  const double e_star = m.young / (1 - m.poisson * m.poisson);
  const double mass = m.density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const double d = std::pow(15 * mass * v * v / (16 * e_star * std::sqrt(r)), 0.4);
  return {.overlap = d,
          .force = 4.0 / 3.0 * e_star * std::sqrt(r) * std::pow(d, 1.5),
          .duration = 2.9432 * d / v};
}

struct Impact {
  double peak_force = 0;  // N, largest |contact force on the recorded body|
  double duration = 0;    // s, time with a non-zero force
  double drift = 0;       // largest |E − E₀| / E₀
  Vec3 v_before = Vec3::Zero(), v_after = Vec3::Zero();  // recorded body's centre-of-mass velocity
  long steps = 0;
  double dt = 0;
};

// Steps at dt = safety × the predicted critical step until the recorded body (body 0) has been
// in contact and separated again (or t_max): the peak force, the energy drift and the velocities
// before and after. `touching(out)` is called after every step with a contact force, e.g. to
// measure the duration.
template <class Touching>
Impact step_impact(World& w, double t_max, double safety, Touching touching) {
  Impact out;
  out.dt = safety * critical_step(w).critical;
  w.want_energy = true;
  const double e0 = energy(w).total();
  out.v_before = body_velocity(w, 0);
  bool touched = false;
  while (w.time < t_max && w.failure.empty()) {
    step(w, out.dt);
    const double f = w.contacts.force.col(0).norm();
    out.peak_force = std::max(out.peak_force, f);
    out.drift = std::max(out.drift, std::abs(energy(w).total() - e0) / e0);
    if (f > 0) {
      touched = true;
      touching(out);
    } else if (touched) {
      break;
    }
  }
  out.v_after = body_velocity(w, 0);
  out.steps = w.steps;
  return out;
}

// The impact with its duration counted in whole steps with a force.
inline Impact run_impact(World& w, double t_max, double safety = 0.5) {
  return step_impact(w, t_max, safety, [](Impact& out) { out.duration += out.dt; });
}

}  // namespace asperity::fdem::scenes
