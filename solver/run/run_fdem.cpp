// The FEM/DEM path of `asperity run`: mesh bodies (model "rigid" or "fem") against each other
// and against fixed boxes and planes, in Munjiza's potential contact (fdem/fdem_world.hpp),
// through the shared step policy, time loop and summary core. Only what is FEM/DEM-specific is
// here: building the world from the scene, its step prediction, its summary keys.
#include "solver/run/run_fdem.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>

#include "solver/contact/munjiza_potential.hpp"
#include "solver/core/error.hpp"
#include "solver/core/format.hpp"
#include "solver/fdem/fdem_world.hpp"
#include "solver/fdem/runaway_penetration.hpp"
#include "solver/fdem/structured_mesh.hpp"
#include "solver/fdem/time_step.hpp"
#include "solver/fem/tet_elements.hpp"
#include "solver/io/json_file.hpp"
#include "solver/run/prepared_meshes.hpp"
#include "solver/run/summary.hpp"
#include "solver/run/time_loop.hpp"
#include "solver/run/vtk_series.hpp"

namespace asperity::run {
namespace {

// The contact's largest share of the step in a scene that leaves the penalty to the solver
// (contact.max_contact_factor; issue 11, item 5: never more than 2× below the element limit).
constexpr double kDefaultContactFactor = 2;

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
  int record = -1;              // the recorded body, world index
};

Built build(const scene::SceneDef& s) {
  const std::string where = s.file.string() + ": ";
  const bool volume_law = s.contact.law == scene::ContactLaw::volume_hertz ||
                          s.contact.law == scene::ContactLaw::volume_linear;
  if (s.contact.law != scene::ContactLaw::potential && !volume_law) {
    throw InputError(where +
                     "contact.law: mesh bodies collide through \"potential\" (Munjiza's "
                     "distributed potential), \"volume-hertz\" or \"volume-linear\"");
  }
  if (s.contact.restitution) {
    throw InputError(where +
                     "contact.restitution: the potential and volume laws are elastic (energy is "
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
    if (volume_law && body.model == scene::Model::fem && !body.fixed) {
      throw InputError(
          key + "model: the volume laws are for rigid bodies (contact.law \"" +
          (s.contact.law == scene::ContactLaw::volume_hertz ? "volume-hertz" : "volume-linear") +
          "\"); use model \"rigid\" or contact.law \"potential\"");
    }
    if (const auto* mesh = std::get_if<scene::MeshShape>(&body.shape)) {
      d.mesh = centred_at(mesh_body(*mesh, key, body.model == scene::Model::fem && !body.fixed),
                          body.position);
      d.kind = body.fixed ? fdem::BodyKind::fixed
                          : (body.model == scene::Model::fem ? fdem::BodyKind::deformable
                                                             : fdem::BodyKind::rigid);
      if (!body.fixed) {
        d.velocity = body.velocity;
        d.angular_velocity = body.angular_velocity;
      }
      d.damping_ratio = body.damping_ratio;
    } else if (const auto* box = std::get_if<scene::BoxShape>(&body.shape)) {
      // A fixed block: its box as six tetrahedra with fixed nodes, the same potential target as
      // any element.
      d.kind = fdem::BodyKind::fixed;
      d.mesh = fdem::box_mesh(box->min, box->max, 1, 1, 1);
    } else if (const auto* plane = std::get_if<scene::PlaneShape>(&body.shape)) {
      planes.emplace_back(static_cast<int>(b), plane);
      continue;  // sized once every other body is known
    } else {
      throw InputError(key + (volume_law ? "shape: the volume laws need rigid mesh bodies (a "
                                           "faceted sphere is shape \"mesh\")"
                                         : "shape: spheres cannot share a scene with mesh bodies "
                                           "(mesh the sphere: shape \"mesh\")"));
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
  out.def.contact.law =
      s.contact.law == scene::ContactLaw::volume_hertz
          ? fdem::ContactLaw::volume_hertz
          : (s.contact.law == scene::ContactLaw::volume_linear ? fdem::ContactLaw::volume_linear
                                                               : fdem::ContactLaw::potential);
  out.def.contact.kv = s.contact.kv.value_or(0.0);
  if (s.contact.penalty_alpha) out.def.contact.alpha = *s.contact.penalty_alpha;
  // The contact's share of the step (issue 11, item 5; docs/physics.md, "Time step"): a scene that
  // gives no penalty, penalty_alpha or max_contact_factor gets max_contact_factor 2 met by
  // face-penalty (the penalty lowered only on the faces whose nodes set the step: 0.0 % of the
  // peak force on 8 of 10 bench_fem particles, −2.2 % at worst, against −4 % to −15 % for one
  // lowered penalty, reports/fem/mesh_step.md). A given penalty or α is used as given unless
  // max_contact_factor is given too.
  const bool penalty_given = s.contact.penalty || s.contact.penalty_alpha;
  out.def.contact.max_contact_factor =
      s.contact.max_contact_factor.value_or(penalty_given ? 0.0 : kDefaultContactFactor);
  switch (s.contact.contact_factor_by) {
    case scene::ContactFactorBy::face_penalty:
      out.def.contact.contact_step_fix = fdem::ContactStepFix::face_penalty;
      break;
    case scene::ContactFactorBy::penalty:
      out.def.contact.contact_step_fix = fdem::ContactStepFix::penalty;
      break;
    case scene::ContactFactorBy::mass:
      out.def.contact.contact_step_fix = fdem::ContactStepFix::mass;
      break;
  }
  out.def.contact.max_added_mass = s.contact.max_added_mass.value_or(0.0);
  // Coulomb μ: the scene's, else the smallest of the bodies' materials (as pair_friction does
  // for a pair).
  out.def.contact.friction = s.contact.friction.value_or(friction);
  // The volume laws' friction is a tangential spring with a Coulomb cap. volume-hertz takes
  // Mindlin's k_t = 8 G* a from the overlap's cross-section (fdem/volume_contact.cpp,
  // volume_friction); volume-linear's kt, as in YADE's volumetric law, has no default (its normal
  // stiffness k_v |S| varies with the overlap, so no one ratio to it is the right one): friction
  // without it is refused.
  if (s.contact.law == scene::ContactLaw::volume_linear && out.def.contact.friction > 0) {
    if (!s.contact.kt) {
      throw InputError(where + "contact.kt: the volume laws' friction (" +
                       (s.contact.friction ? "contact.friction " : "the materials' friction ") +
                       fmt(out.def.contact.friction) +
                       ") needs kt, the tangential stiffness in N/m; or set contact.friction to 0");
    }
    out.def.contact.kt = *s.contact.kt;
  }
  for (std::size_t i = 0; i < out.scene_body.size(); ++i) {
    if (out.scene_body[i] == s.record.body) out.record = static_cast<int>(i);
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

// The FEM/DEM world as the time loop sees it (run/time_loop.hpp).
struct FdemModel {
  fdem::World& w;
  fdem::RunawayPenetration runaway;
  int record = -1;
  int partner = -1;  // world body, -1: the fixed targets
  long every = 1;
  double max_penetration = 0;  // largest World::penetration, for the summary

  // Energy needs the contact energy integrals (extra clipping): computed only when asked.
  void prepare(bool energy_wanted) { w.want_energy = energy_wanted; }
  void step(double dt) {
    fdem::step(w, dt);
    max_penetration = std::max(max_penetration, w.penetration);
  }
  std::string failure() {
    if (!w.failure.empty()) return w.failure;
    return runaway.check(w);
  }
  const BodyContacts& contacts() const { return w.contacts; }
  Vec3 relative_velocity() const {
    const Vec3 v = fdem::body_velocity(w, record);
    return partner >= 0 ? Vec3(v - fdem::body_velocity(w, partner)) : v;
  }
  EnergyBalance energy() const { return fdem::energy(w); }
  bool finite() const { return w.x.allFinite(); }
  double time() const { return w.time; }
  // Checked at most every 20 steps, and at every recorded row.
  long check_every() const { return std::min(20L, every); }
};

// The world, checked: no body may start inside another (the first step would fire it out with
// a spurious force), and something must move.
fdem::World checked_world(const scene::SceneDef& s, const Built& built) {
  const std::string where = s.file.string() + ": ";
  fdem::World w = fdem::make_world(built.def);
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
  return w;
}

StepPrediction prediction_of(const scene::SceneDef& s, const fdem::CriticalStep& crit) {
  if (!std::isfinite(crit.critical)) {
    throw InputError(s.file.string() + ": bodies: nothing moves (every body is fixed)");
  }
  // The potential contact's shortest duration has no closed form: only the duration bounds it.
  return {.critical = crit.critical,
          .limited_by = crit.limited_by,
          .shortest_contact = std::numeric_limits<double>::infinity()};
}

StepRegime regime_of(const fdem::World& w) {
  if (w.law != fdem::ContactLaw::potential) return StepRegime::fdem_volume;
  for (const fdem::Body& b : w.bodies) {
    if (b.kind == fdem::BodyKind::deformable) return StepRegime::fdem_deformable;
  }
  return StepRegime::fdem_rigid;
}

}  // namespace

std::vector<TetMesh> collision_meshes(const scene::SceneDef& s) {
  Built built = build(s);
  std::vector<TetMesh> out(s.bodies.size());
  for (std::size_t i = 0; i < built.scene_body.size(); ++i) {
    out[static_cast<std::size_t>(built.scene_body[i])] = std::move(built.def.bodies[i].mesh);
  }
  return out;
}

bool is_fdem_scene(const scene::SceneDef& s) {
  if (s.contact.law == scene::ContactLaw::potential ||
      s.contact.law == scene::ContactLaw::volume_hertz ||
      s.contact.law == scene::ContactLaw::volume_linear) {
    return true;
  }
  return std::any_of(s.bodies.begin(), s.bodies.end(), [](const scene::BodyDef& b) {
    return std::holds_alternative<scene::MeshShape>(b.shape);
  });
}

StepChoice fdem_step(const scene::SceneDef& s, const RunOptions& options) {
  const Built built = build(s);
  const fdem::World w = checked_world(s, built);
  return choose_step(s, options, prediction_of(s, fdem::critical_step(w)), regime_of(w));
}

RunResult run_fdem(const scene::SceneDef& s, const RunOptions& options) {
  const Built built = build(s);
  fdem::World w = checked_world(s, built);
  const fdem::CriticalStep crit = fdem::critical_step(w);
  const StepPrediction prediction = prediction_of(s, crit);
  const StepChoice step = choose_step(s, options, prediction, regime_of(w));
  const RunIdentity id{.scene = s.name,
                       .model = "fdem",
                       .contact_law = scene::contact_law_name(s.contact.law),
                       .recorded_body = s.bodies[s.record.body].name};
  if (!step.unresolved.empty()) return unresolved_run(id, step, prediction);

  std::vector<bool> free;
  for (const fdem::Body& b : w.bodies) free.push_back(b.kind != fdem::BodyKind::fixed);
  FdemModel m{.w = w,
              .runaway = fdem::RunawayPenetration(w, built.def),
              .record = built.record,
              .partner = restitution_partner(built.record, free),
              .every = std::max(1, s.record.every)};

  // ParaView frames: an observer of the loop (each body's tetrahedra in world node indices).
  std::optional<FdemSeries> frames;
  if (options.vtk && options.vtk->every > 0) {
    std::vector<Eigen::Matrix4Xi> tets;
    for (std::size_t b = 0; b < w.bodies.size(); ++b) {
      tets.push_back(built.def.bodies[b].mesh.tets.array() + w.bodies[b].node_begin);
    }
    frames.emplace(w, tets, *options.vtk);
  }

  RunResult result;
  const LoopOutcome loop = run_model(m, frames, id, s, options, step, result);
  using J = SummaryJson;
  auto& j = result.summary;
  // The raw peak_force beside the first contact's peak low-passed over a twentieth of its
  // duration and that contact's raw / filtered − 1 (docs/physics.md, issue 11).
  j["peak_force_filtered"] = loop.impact.filtered_peak();
  j["ringing_amplitude"] = loop.impact.ringing_amplitude();
  // Largest overlap depth / contacting element's centroid height (runaway penetration at 0.5).
  j["max_penetration_ratio"] = m.max_penetration;
  write_step(j, step, prediction);
  j["dt_element"] = std::isfinite(crit.element) ? J(crit.element) : J();
  j["dt_contact"] = std::isfinite(crit.contact) ? J(crit.contact) : J();
  if (w.law == fdem::ContactLaw::potential) {
    j["penalty"] = w.penalty;
    // α actually used (p/E: below the default 10 when limit_penalty lowered it) and the α asked.
    const double used = built.def.contact.alpha * w.penalty / w.penalty_asked;
    j["penalty_alpha"] = s.contact.penalty ? J() : J(used);
    j["penalty_alpha_asked"] = s.contact.penalty ? J() : J(built.def.contact.alpha);
    // What met max_contact_factor: the least face penalty scale (face-penalty) and the mass
    // added to the surface nodes over the moving bodies' mass (mass).
    j["max_contact_factor"] = w.contact_factor;
    double least = 1;
    for (const double x : w.tet_penalty_scale) least = std::min(least, x);
    j["penalty_scale_min"] = least;
    double added = 0, moving = 0;
    for (const double x : w.added_mass) added += x;
    for (const fdem::Body& b : w.bodies) {
      if (b.kind != fdem::BodyKind::fixed) moving += b.mass;
    }
    j["added_mass_fraction"] = moving > 0 ? added / moving : 0.0;
  } else if (w.law == fdem::ContactLaw::volume_linear) {
    j["kv"] = w.kv;
  }
  j["friction"] = w.friction;
  // The recorded body's elastic law when it is deformable (docs/physics.md: the linear law is for
  // validation against linear-elastic solutions only).
  const fdem::Body& recorded = w.bodies[built.record];
  j["material_law"] = recorded.kind == fdem::BodyKind::deformable
                          ? J(elastic_law_name(recorded.material.law))
                          : J();
  write_run(j, w.steps, w.time, loop.ended_by_separation, loop.cpu_seconds, loop.wall_seconds);
  j["profile"] = profile_json(w.profile, loop.seconds_per_tick, true);
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
  if (w.bodies[built.record].kind == fdem::BodyKind::rigid) {
    // The recorded rigid body's motion at the end (the rebound the peers compare).
    const fdem::RigidBody& rb = w.rigid[w.bodies[built.record].rigid];
    j["final_velocity"] = {rb.velocity.x(), rb.velocity.y(), rb.velocity.z()};
    j["final_angular_velocity"] = {rb.omega.x(), rb.omega.y(), rb.omega.z()};
    j["final_speed"] = rb.velocity.norm();
    j["final_spin"] = rb.omega.norm();
  }
  j["surface_tets"] = w.surface_tets.cols();
  return result;
}

}  // namespace asperity::run
