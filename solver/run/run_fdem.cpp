// Scene → FEM/DEM world → time loop → measures, for mesh bodies (fdem/fdem_world.hpp).
#include "run/run_fdem.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <optional>
#include <sstream>

#include "contact/munjiza_potential.hpp"
#include "core/error.hpp"
#include "fdem/fdem_world.hpp"
#include "fdem/structured_mesh.hpp"
#include "fdem/time_step.hpp"
#include "fem/tet_elements.hpp"
#include "run/impact_measures.hpp"
#include "run/run_monitor.hpp"
#if ASPERITY_HAVE_GEOMETRY
#include "geometry/mesh_pipeline.hpp"
#endif

namespace asperity::run {
namespace {

std::string fmt(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

double cpu_seconds() {
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

// FEM/DEM default dt_safety (the sphere DEM's 0.01 resolves a Hertz contact in ~200 steps).
// Here the step is set by element and penalty stiffness, each contact spans thousands of steps
// at the critical one, and the bound is already conservative (element eigenvalue and
// Gershgorin bounds), so the FEM/DEM default is 0.5 unless the scene gives its own factor.
constexpr double kFdemSafety = 0.5;
// Without a moving deformable body nothing but the contact springs sets the step, and the rigid
// bound over the pressed patch (fdem/time_step.hpp) is sharp, so 0.5 of it resolves a contact
// in only 10–15 steps: the peak force was 0.4–0.8 % off the converged-step value on three
// particles of the study at 250 and 1000 triangles, 0.02–0.06 % at 0.1, for a cost that stays
// a fraction of a second. Rigid-only scenes therefore default to 0.1.
constexpr double kRigidSafety = 0.1;

// Runaway penetration (an instability criterion beside the energy check). The potential of an
// element rises from 0 on its faces to 1 at its centroid (contact/munjiza_potential.hpp), and the
// penalty force on a point grows with it only up to there: past the centroid the point is in
// another sub-tetrahedron and is pushed on, out through the far side. A contact whose deepest
// point has gone half-way to the contacting element's centroid (World::penetration ≥ 0.5) is
// tunnelling the penalty: a healthy contact at α = 10 stays below a few per cent (its
// penetration is about a tenth of the element's elastic shortening), so 0.5 leaves an order of
// magnitude of margin while still stopping the run before the node reaches the centroid, at
// which point the force reverses. Energy is conserved while a body tunnels, so the energy check
// alone cannot see it.
constexpr double kRunawayPenetration = 0.5;

// The second half of the criterion: a body passed through another when its centre, on its way
// through the last step, entered the other's tetrahedra (taken where they are at the end of the
// step). Checked every step, for bodies whose centre lies in their own material at the start (a
// hollow or hooked body's centre may legitimately lie in another). It catches a body that sank
// into a far larger element, where the depth ratio stays small, and one that jumped through a
// body within a single step, which no contact ever saw.
struct BodyTets {
  Eigen::Matrix4Xi tets;  // global node indices
  int node_begin = 0, node_end = 0;
  bool centre_inside_itself = false;
};

// Whether the segment p0 → p1 meets a tetrahedron of b: along it each barycentric coordinate is
// linear, so the part inside a tetrahedron is the interval where all four are ≥ 0.
bool path_meets_body(const fdem::World& w, const BodyTets& b, const Vec3& p0, const Vec3& p1) {
  const Vec3 seg_lo = p0.cwiseMin(p1), seg_hi = p0.cwiseMax(p1);
  const auto nodes = w.x.middleCols(b.node_begin, b.node_end - b.node_begin);
  if ((seg_hi.array() < nodes.rowwise().minCoeff().array()).any() ||
      (seg_lo.array() > nodes.rowwise().maxCoeff().array()).any()) {
    return false;
  }
  for (Eigen::Index k = 0; k < b.tets.cols(); ++k) {
    contact::TetNodes t;
    Vec3 lo = w.x.col(b.tets(0, k)), hi = lo;
    for (int i = 0; i < 4; ++i) {
      t[i] = w.x.col(b.tets(i, k));
      lo = lo.cwiseMin(t[i]), hi = hi.cwiseMax(t[i]);
    }
    if ((seg_hi.array() < lo.array()).any() || (seg_lo.array() > hi.array()).any()) continue;
    const Eigen::Vector4d l0 = contact::barycentric(t, p0), l1 = contact::barycentric(t, p1);
    double s_lo = 0, s_hi = 1;
    for (int i = 0; i < 4 && s_lo <= s_hi; ++i) {
      const double d = l1[i] - l0[i];  // L_i(s) = l0 + s d ≥ 0
      if (d > 0) {
        s_lo = std::max(s_lo, -l0[i] / d);
      } else if (d < 0) {
        s_hi = std::min(s_hi, -l0[i] / d);
      } else if (l0[i] < 0) {
        s_hi = -1;
      }
    }
    if (s_lo <= s_hi) return true;
  }
  return false;
}

TetMesh mesh_body(const scene::MeshShape& m, const std::string& key) {
#if ASPERITY_HAVE_GEOMETRY
  geometry::PipelineOptions o;
  o.faces = m.faces;
  o.read.scale = m.scale;
  o.tetrahedralize = true;
  o.tet.element_size.size = m.element_size;
  o.element_size_key = key + "shape.element_size";
  return geometry::prepare_particle(m.file, o).tets;
#else
  (void)m;
  throw InputError(key +
                   "shape: mesh bodies need the geometry pipeline (solver/geometry), "
                   "which is not in this build");
#endif
}

TetMesh centred_at(TetMesh m, const Vec3& position) {
  double vol = 0;
  Vec3 first = Vec3::Zero();
  for (Eigen::Index k = 0; k < m.tets.cols(); ++k) {
    const Vec3 a = m.nodes.col(m.tets(0, k)), b = m.nodes.col(m.tets(1, k)),
               c = m.nodes.col(m.tets(2, k)), d = m.nodes.col(m.tets(3, k));
    const double v = (b - a).cross(c - a).dot(d - a) / 6;
    vol += v;
    first += v * 0.25 * (a + b + c + d);
  }
  m.nodes.colwise() += position - first / vol;
  return m;
}

struct Built {
  fdem::WorldDef def;
  std::vector<int> scene_body;  // world body → scene body
};

Built build(const scene::SceneDef& s) {
  const std::string where = s.file.string() + ": ";
  if (s.contact.law != scene::ContactLaw::potential) {
    throw InputError(where +
                     "contact.law: mesh bodies collide through \"potential\" (Munjiza's "
                     "distributed potential); set contact.law to \"potential\"");
  }
  if (s.contact.restitution) {
    throw InputError(where +
                     "contact.restitution: the potential law is elastic (energy is "
                     "lost only to friction and element damping); remove the key");
  }
  Built out;
  double friction = 1e300;
  std::vector<std::pair<int, const scene::PlaneShape*>> planes;
  Eigen::AlignedBox3d extent;
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    const scene::BodyDef& body = s.bodies[b];
    const std::string key = where + "bodies[" + std::to_string(b) + "] \"" + body.name + "\": ";
    const Material& mat = s.materials[body.material];
    friction = std::min(friction, mat.friction);
    fdem::BodyDef d{.name = body.name, .material = mat};
    if (const auto* mesh = std::get_if<scene::MeshShape>(&body.shape)) {
      d.mesh = centred_at(mesh_body(*mesh, key), body.position);
      d.kind = body.fixed ? fdem::BodyKind::fixed
                          : (body.model == scene::Model::fem ? fdem::BodyKind::deformable
                                                             : fdem::BodyKind::rigid);
      if (!body.fixed) {
        d.velocity = body.velocity;
        d.angular_velocity = body.angular_velocity;
      }
      if (body.damping_ratio > 0) {
        // ξ = β ω / 2 for stiffness-proportional damping (fem/tet_elements.hpp), at the body's
        // highest element frequency.
        const fem::TetElements e = fem::make_tet_elements(
            d.mesh.nodes, d.mesh.tets, mat.young, mat.poisson, mat.density, 0, key + "mesh");
        d.damping = 2 * body.damping_ratio / fem::element_critical_step(e).omega_max;
      }
    } else if (const auto* box = std::get_if<scene::BoxShape>(&body.shape)) {
      // A fixed block: its box as six tetrahedra with fixed nodes, the same potential target as
      // any element.
      d.kind = fdem::BodyKind::fixed;
      d.mesh = fdem::box_mesh(box->min, box->max, 1, 1, 1);
    } else if (const auto* plane = std::get_if<scene::PlaneShape>(&body.shape)) {
      planes.emplace_back(static_cast<int>(b), plane);
      continue;  // sized once every other body is known
    } else {
      throw InputError(key +
                       "shape: spheres cannot share a scene with mesh bodies (mesh the "
                       "sphere: shape \"mesh\")");
    }
    for (Eigen::Index i = 0; i < d.mesh.nodes.cols(); ++i) extent.extend(d.mesh.nodes.col(i));
    out.def.bodies.push_back(std::move(d));
    out.scene_body.push_back(static_cast<int>(b));
  }
  for (const auto& [b, plane] : planes) {
    // A plane becomes a fixed slab under it, wide and deep enough that nothing in the scene can
    // reach its edges: half-width and depth 4× the largest distance of any node from the plane's
    // point (plus 1 m when the scene is a single point).
    double reach = 1.0;
    if (!extent.isEmpty()) {
      for (int c = 0; c < 8; ++c) {
        reach = std::max(
            reach,
            (extent.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)) - plane->point).norm());
      }
    }
    const Vec3 n = plane->normal.normalized();
    const Vec3 t1 = n.unitOrthogonal(), t2 = n.cross(t1);
    Mat3 frame;
    frame << t1, t2, n;
    const double l = 4 * reach;
    fdem::BodyDef d{.name = s.bodies[b].name,
                    .kind = fdem::BodyKind::fixed,
                    .mesh = fdem::oriented_box_mesh(plane->point, frame, Vec3(-l, -l, -l),
                                                    Vec3(l, l, 0), 1, 1, 1),
                    .material = s.materials[s.bodies[b].material]};
    out.def.bodies.push_back(std::move(d));
    out.scene_body.push_back(b);
  }
  out.def.gravity = s.gravity;
  out.def.contact.penalty = s.contact.penalty.value_or(0.0);
  // Coulomb μ: the scene's, else the smallest of the bodies' materials (as pair_friction does
  // for a pair).
  out.def.contact.friction = s.contact.friction.value_or(friction);
  for (std::size_t i = 0; i < out.scene_body.size(); ++i) {
    if (out.scene_body[i] == s.record.body) out.def.record_body = static_cast<int>(i);
  }
  return out;
}

const char* kind_name(fdem::BodyKind k) {
  switch (k) {
    case fdem::BodyKind::deformable:
      return "fem";
    case fdem::BodyKind::rigid:
      return "rigid";
    case fdem::BodyKind::fixed:
      return "fixed";
  }
  return "?";
}

}  // namespace

bool is_fdem_scene(const scene::SceneDef& s) {
  if (s.contact.law == scene::ContactLaw::potential) return true;
  return std::any_of(s.bodies.begin(), s.bodies.end(), [](const scene::BodyDef& b) {
    return std::holds_alternative<scene::MeshShape>(b.shape);
  });
}

RunResult run_fdem(const scene::SceneDef& s, const RunOptions& options) {
  const std::string where = s.file.string() + ": ";
  const Built built = build(s);
  fdem::World w = fdem::make_world(built.def);
  // No body may start inside another: the first step would fire it out with a spurious force.
  if (w.contacts_touching > 0) {
    for (const fdem::TetPair& p : w.pairs) {
      const int a = w.surface_tet_body[p.a], b = w.surface_tet_body[p.b];
      contact::TetNodes ta, tb;
      for (int i = 0; i < 4; ++i) {
        ta[i] = w.x.col(w.surface_tets(i, p.a));
        tb[i] = w.x.col(w.surface_tets(i, p.b));
      }
      const auto c = contact::munjiza_potential(ta, tb, w.penalty, false);
      if (c.touching()) {
        throw InputError(where + "bodies \"" + w.bodies[a].name + "\" and \"" + w.bodies[b].name +
                         "\": position: they start overlapping (by " + fmt(c.depth) +
                         " m or more)");
      }
    }
  }
  const fdem::CriticalStep crit = fdem::critical_step(w);
  if (!std::isfinite(crit.critical)) {
    throw InputError(where + "bodies: nothing moves (every body is fixed)");
  }

  bool deformable_moves = false;
  for (const fdem::Body& b : w.bodies) deformable_moves |= b.kind == fdem::BodyKind::deformable;
  const double safety = s.dt_safety.value_or(deformable_moves ? kFdemSafety : kRigidSafety);
  double dt = 0;
  bool auto_dt = false;
  if (options.dt_factor) {
    dt = *options.dt_factor * crit.critical;
  } else if (const std::optional<double> given = options.dt ? options.dt : s.dt) {
    dt = *given;
    if (dt > crit.critical && !(options.allow_unsafe_dt || s.allow_unsafe_dt)) {
      throw InputError(where + "dt: " + fmt(dt) + " s exceeds the predicted critical step " +
                       fmt(crit.critical) + " s (limited by " + crit.limited_by +
                       "); use \"auto\", a smaller dt, or allow_unsafe_dt: true");
    }
  } else {
    dt = safety * crit.critical;
    auto_dt = true;
  }
  const double n_steps_real = std::ceil(s.duration / dt - 1e-9);
  if (n_steps_real > 2e9) {
    throw InputError(where + "duration: " + fmt(s.duration) + " s needs " + fmt(n_steps_real) +
                     " steps of " + fmt(dt) + " s (over 2e9)");
  }
  const long n_steps = static_cast<long>(n_steps_real);

  // The partner whose velocity the restitution is measured against: the other free body when
  // there are exactly two, else the fixed targets (velocity zero).
  int partner = -1;
  {
    std::vector<int> free;
    for (std::size_t b = 0; b < w.bodies.size(); ++b) {
      if (w.bodies[b].kind != fdem::BodyKind::fixed) free.push_back(static_cast<int>(b));
    }
    if (free.size() == 2) partner = free[0] == w.record_body ? free[1] : free[0];
  }
  auto relative_velocity = [&] {
    const Vec3 v = fdem::body_velocity(w, w.record_body);
    return partner >= 0 ? Vec3(v - fdem::body_velocity(w, partner)) : v;
  };

  std::vector<BodyTets> body_tets(w.bodies.size());
  for (std::size_t b = 0; b < w.bodies.size(); ++b) {
    body_tets[b].tets = built.def.bodies[b].mesh.tets.array() + w.bodies[b].node_begin;
    body_tets[b].node_begin = w.bodies[b].node_begin;
    body_tets[b].node_end = w.bodies[b].node_end;
    body_tets[b].centre_inside_itself =
        w.bodies[b].kind != fdem::BodyKind::fixed &&
        path_meets_body(w, body_tets[b], fdem::body_centre(w, static_cast<int>(b)),
                        fdem::body_centre(w, static_cast<int>(b)));
  }
  std::vector<Vec3> centre_before(w.bodies.size());
  for (std::size_t b = 0; b < w.bodies.size(); ++b) {
    centre_before[b] = fdem::body_centre(w, static_cast<int>(b));
  }
  auto body_name = [&](int b) { return "\"" + w.bodies[b].name + "\""; };
  auto check_penetration = [&](RunMonitor& monitor) {
    if (w.penetration >= kRunawayPenetration) {
      monitor.flag("runaway penetration: bodies " + body_name(w.penetration_body_a) + " and " +
                   body_name(w.penetration_body_b) + " overlap " + fmt(w.penetration) +
                   " of the way to an element's centre (limit " + fmt(kRunawayPenetration) +
                   ") at t = " + fmt(w.time) + " s");
      return;
    }
    for (std::size_t a = 0; a < w.bodies.size(); ++a) {
      if (!body_tets[a].centre_inside_itself) continue;
      const Vec3 c = fdem::body_centre(w, static_cast<int>(a));
      for (std::size_t b = 0; b < w.bodies.size(); ++b) {
        if (b != a && path_meets_body(w, body_tets[b], centre_before[a], c)) {
          monitor.flag("runaway penetration: body " + body_name(static_cast<int>(a)) +
                       " passed through " + body_name(static_cast<int>(b)) +
                       " (its centre entered it) at t = " + fmt(w.time) + " s");
          return;
        }
      }
      centre_before[a] = c;
    }
  };

  RunResult result;
  const auto wall0 = std::chrono::steady_clock::now();
  const double cpu0 = cpu_seconds();
  ImpactMeasures im;
  im.start(0, w.record_force, w.record_depth);
  const fdem::EnergyTerms e0 = fdem::energy(w);
  auto balance = [](const fdem::EnergyTerms& e) {
    return EnergyBalance{.kinetic = e.kinetic,
                         .elastic = e.elastic,
                         .contact = e.contact,
                         .gravity = e.gravity,
                         .dissipated = e.dissipated};
  };
  RunMonitor monitor(s.name, balance(e0), s.unstable_energy_growth, n_steps, options.progress);
  auto push_rows = [&](const fdem::EnergyTerms& e) {
    if (!options.keep_rows) return;
    const Vec3& f = w.record_force;
    result.force.push_back({w.time, f.x(), f.y(), f.z(), f.norm()});
    result.energy.push_back(
        {w.time, e.kinetic, e.elastic, e.contact, e.gravity, e.dissipated, e.total()});
  };
  push_rows(e0);
  // Energy needs the contact energy integrals (extra clipping), so it is checked at most every
  // 20 steps, and at every recorded row.
  const long check_every = std::min(20, std::max(1, s.record.every));
  Vec3 impulse = Vec3::Zero(), v_approach = Vec3::Zero(), v_separation = Vec3::Zero();
  bool was_touching = im.touching, ended = false, ended_by_separation = false;
  double max_penetration = 0;  // largest World::penetration, for the summary
  for (long k = 1; k <= n_steps && !monitor.unstable(); ++k) {
    const bool row = k % s.record.every == 0 || k == n_steps;
    w.want_energy = row || k % check_every == 0;
    const Vec3 v_before = relative_velocity();
    fdem::step(w, dt);
    if (!w.failure.empty()) {
      monitor.flag(w.failure);
      break;
    }
    max_penetration = std::max(max_penetration, w.penetration);
    check_penetration(monitor);
    if (monitor.unstable()) break;
    im.add(w.time, w.record_force, w.record_depth);
    impulse += w.record_force * dt;
    if (!was_touching && im.touching && im.first_contact_time >= 0 && v_approach.isZero()) {
      v_approach = v_before;
    }
    if (was_touching && !im.touching && !ended) {
      v_separation = relative_velocity();
      ended = true;
    }
    was_touching = im.touching;
    ended_by_separation =
        s.record.end_after_separation && im.separated_for(w.time, *s.record.end_after_separation);
    if (w.want_energy) {
      const fdem::EnergyTerms e = fdem::energy(w);
      monitor.check_energy(w.time, balance(e), w.x.allFinite());
      if (row) push_rows(e);
    }
    monitor.progress(k);
    if (ended_by_separation) {
      if (!row) push_rows(fdem::energy(w));  // the last state, where the run stopped
      break;
    }
  }
  monitor.finish();
  const double cpu = cpu_seconds() - cpu0;
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();

  result.status = monitor.status(im.first_contact_time >= 0);
  result.message = monitor.message();
  const double drift = monitor.drift();
  const std::string& unstable = monitor.message();
  using J = nlohmann::ordered_json;
  auto& j = result.summary;
  j["status"] = result.status;
  if (!unstable.empty()) j["message"] = unstable;
  j["scene"] = s.name;
  j["model"] = "fdem";
  j["contact_law"] = "potential";
  j["recorded_body"] = s.bodies[s.record.body].name;
  j["peak_force"] = im.peak_force;
  // The raw peak above, beside the first contact's peak low-passed over a twentieth of its
  // duration and that contact's raw / filtered − 1 (docs/physics.md, issue 11).
  j["peak_force_filtered"] = im.filtered_peak();
  j["ringing_amplitude"] = im.ringing_amplitude();
  j["impulse"] = im.impulse;
  j["contact_duration"] = im.duration_until(w.time);
  j["first_contact_time"] = im.first_contact_time < 0 ? J() : J(im.first_contact_time);
  j["max_overlap"] = im.max_overlap;
  // Largest overlap depth / contacting element's centroid height (runaway penetration at 0.5).
  j["max_penetration_ratio"] = max_penetration;
  // e = −(v_sep · n) / (v_app · n), n the direction of the recorded body's contact impulse,
  // velocities of its centre of mass relative to the partner's, at the first contact's start and
  // end.
  const double in_speed = impulse.norm() > 0 ? -v_approach.dot(impulse.normalized()) : 0;
  j["restitution"] =
      (ended && in_speed > 0) ? J(v_separation.dot(impulse.normalized()) / in_speed) : J();
  j["energy_drift"] = drift;
  j["dt"] = dt;
  j["dt_critical_predicted"] = crit.critical;
  j["dt_element"] = std::isfinite(crit.element) ? J(crit.element) : J();
  j["dt_contact"] = std::isfinite(crit.contact) ? J(crit.contact) : J();
  j["dt_limited_by"] = crit.limited_by;
  j["dt_safety"] = auto_dt ? J(safety) : J();
  j["penalty"] = w.penalty;
  j["penalty_alpha"] = s.contact.penalty ? J() : J(built.def.contact.alpha);
  j["friction"] = w.friction;
  j["steps"] = w.steps;
  j["simulated_time"] = w.time;
  j["ended_by"] = ended_by_separation ? "separation" : "duration";
  j["cpu_seconds"] = cpu;
  j["wall_seconds"] = wall;
  j["profile"] = {{"broad_phase", w.profile.broad_phase},
                  {"contact", w.profile.contact},
                  {"internal_forces", w.profile.internal},
                  {"integrate", w.profile.integrate}};
  j["neighbour_rebuilds"] = w.rebuilds;
  j["contact_evaluations"] = w.contact_evaluations;
  j["contacts_touching"] = w.contacts_touching;
  J bodies = J::array();
  for (const fdem::Body& b : w.bodies) {
    J e = {{"name", b.name},
           {"model", kind_name(b.kind)},
           {"nodes", b.node_end - b.node_begin},
           {"mass", b.mass}};
    if (b.elements >= 0) {
      e["tets"] = w.elements[b.elements].size();
      e["damping"] = w.elements[b.elements].damping;  // Kelvin–Voigt β, s
    }
    bodies.push_back(e);
  }
  j["bodies"] = bodies;
  j["surface_tets"] = w.surface_tets.cols();
  return result;
}

}  // namespace asperity::run
