// The CalculiX adapter (Debian's calculix-ccx 2.20, `ccx`, meshed by Debian's gmsh): a deformable
// `fem` body (a sphere, or any closed surface: a particle) striking a fixed plane or box face
// head-on, frictionless (docs/crosscheck.md, "CalculiX"). scene_to_calculix.py meshes the body
// with gmsh at the scene's element-size keys (graded to the strike point), writes the deck
// (4-node tetrahedra, node-to-face penalty contact on a fixed block, implicit *DYNAMIC), runs ccx
// and reads back the contact force and the strike point's penetration every increment.
//
// What differs from the other peers, and why:
//   step        ccx's own, implicit: T_H/kIncrementsPerHertzTime (asperity's explicit step, about
//               T_H/15 000, would cost 150× the increments an implicit scheme needs: against
//               T_H/200, T_H/100 moves the filtered peak by 0.09 and the duration by 0.04 point,
//               measured at a/R = 0.15, s = 1)
//   end         asperity's end time (the scene's duration under `validate --solver`, which runs
//               no asperity: own_step), or 1.2 T_H after the first touch when that is sooner (the
//               finite sphere's contact is shorter than Hertz's: docs/physics.md, point 6)
//   surface     a sphere's: the exact sphere through the file's vertices (gmsh's OpenCASCADE
//               sphere), not the file's facets: a smooth surface is what both codes converge to.
//               Any other surface's: the file's facets, each a plane surface of gmsh, so both
//               codes mesh the same polyhedron (asperity bisects the facets in their planes)
//   symmetry    a sphere: quarter (the two vertical planes through the strike point), the focus
//               on the axis; a particle: none, the whole body (it has no plane of symmetry)
//   penalty     ccx's linear pressure-overclosure law, slope kPenaltyFactor·E/h (h the element
//               size at the strike point): the layer takes p0 h / (kPenaltyFactor E) of the
//               approach, 0.5 % at a/R = 0.107 and h = 4 mm, and falls with h
//   motion      the body's centroid from the momentum balance of the meshed mass under the
//               contact force and gravity (ccx prints no body motion); a particle's spin from
//               its angular impulse, the force at the strike node, over the meshed inertia
#include <array>
#include <cmath>
#include <fstream>
#include <numbers>
#include <optional>

#include "peers/peer_adapters.hpp"
#include "solver/core/error.hpp"
#include "solver/geometry/read_mesh.hpp"

#ifndef ASPERITY_CALCULIX_SCRIPT
#error "ASPERITY_CALCULIX_SCRIPT (path of peers/scene_to_calculix.py) must be defined by the build"
#endif

namespace asperity::peers {
namespace {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

constexpr double kIncrementsPerHertzTime = 100;
constexpr double kPenaltyFactor = 50;
// A surface is a sphere when every vertex lies within this fraction of the radius from the
// sphere through them (a geodesic sphere's vertices lie on it to round-off; a rock's do not).
constexpr double kSphereTolerance = 1e-6;
// Head-on: the velocity's angle to the plane's normal, and the focus's distance from the axis
// through the sphere's centre (fraction of R), below which the scene is quarter-symmetric.
constexpr double kAxisTolerance = 1e-9;

Json vec(const Vec3& v) {
  return Json::array({v.x(), v.y(), v.z()});
}

// The fem body as placed: a sphere (its centre and radius) or any other closed surface (its
// volume centroid, its placed vertices and triangles, its volume-equivalent radius).
struct Body {
  bool sphere = true;
  Vec3 centre = Vec3::Zero();  // m, the sphere's centre or the surface's centroid, placed
  std::optional<Vec3> focus;   // m, the element size's focus, placed likewise (none: uniform)
  double radius = 0;           // m, the sphere's; a surface's (3V/4π)^{1/3}
  Eigen::Matrix3Xd points;     // m, a surface's vertices, placed
  std::vector<std::array<int, 3>> triangles;  // outward, a surface's polygons as fans
};

// The fixed plane the sphere strikes: a point on it and its unit normal into the free side.
struct Target {
  Vec3 point = Vec3::Zero(), normal = Vec3::UnitZ();
};

struct Problem {
  int ball = -1, target = -1;
  Body body;
  Target plane;
};

std::string at_body(const scene::SceneDef& s, std::size_t k) {
  return s.file.string() + ": bodies[" + std::to_string(k) + "] \"" + s.bodies[k].name + "\": ";
}

// The surface's volume centroid (the point the scene places at `position`) and the sphere through
// its vertices, or the placed surface when it is not one.
Body body_of(const scene::SceneDef& s, std::size_t k) {
  const scene::BodyDef& b = s.bodies[k];
  const auto& shape = std::get<scene::MeshShape>(b.shape);
  const geometry::PolygonSoup soup = geometry::read_mesh_file(shape.file, {.scale = shape.scale});
  // Volume centroid of the closed surface: the sum over fan triangles of the tetrahedra they
  // span with the origin.
  double volume = 0;
  Vec3 moment = Vec3::Zero();
  for (const std::vector<int>& poly : soup.polygons) {
    const Vec3 a = soup.points.col(poly[0]);
    for (std::size_t i = 1; i + 1 < poly.size(); ++i) {
      const Vec3 p = soup.points.col(poly[i]), q = soup.points.col(poly[i + 1]);
      const double v = a.dot(p.cross(q)) / 6;
      volume += v;
      moment += v * (a + p + q) / 4;
    }
  }
  const Vec3 centroid = moment / volume;
  // The sphere through the vertices: least squares of |x|² = 2 c·x + (r² − |c|²), linear in c.
  const Eigen::Index nv = soup.points.cols();
  Eigen::MatrixX4d a(nv, 4);
  Eigen::VectorXd rhs(nv);
  for (Eigen::Index i = 0; i < nv; ++i) {
    a.row(i) << 2 * soup.points.col(i).transpose(), 1.0;
    rhs(i) = soup.points.col(i).squaredNorm();
  }
  const Eigen::Vector4d fit = a.colPivHouseholderQr().solve(rhs);
  const Vec3 mid = fit.head<3>();
  const double r = std::sqrt(std::max(0.0, fit(3) + mid.squaredNorm()));
  double worst = 0;
  for (Eigen::Index i = 0; i < nv; ++i)
    worst = std::max(worst, std::abs((soup.points.col(i) - mid).norm() - r) / r);
  const Vec3 placed = b.position - centroid;
  const std::optional<Vec3> focus = shape.element_size_focus
                                        ? std::optional<Vec3>(*shape.element_size_focus + placed)
                                        : std::nullopt;
  if (worst <= kSphereTolerance)
    return {.sphere = true, .centre = mid + placed, .focus = focus, .radius = r};
  // Not a sphere: the whole surface, as the file gives it (the scene's `faces` would simplify
  // it in asperity, a surface the deck does not see).
  std::size_t triangles = 0;
  for (const std::vector<int>& poly : soup.polygons) triangles += poly.size() - 2;
  if (shape.faces > 0 && static_cast<std::size_t>(shape.faces) != triangles) {
    throw InputError(
        at_body(s, k) + "shape.faces: calculix: meshes the file's " + std::to_string(triangles) +
        " triangles as they are, not a simplification to " + std::to_string(shape.faces) +
        " (simplify the file first: asperity mesh FILE --faces N --no-tets)");
  }
  Body out{.sphere = false,
           .centre = b.position,
           .focus = focus,
           .radius = std::cbrt(3 * volume / (4 * std::numbers::pi)),
           .points = soup.points.colwise() + placed};
  for (const std::vector<int>& poly : soup.polygons)
    for (std::size_t i = 1; i + 1 < poly.size(); ++i)
      out.triangles.push_back({poly[0], poly[i], poly[i + 1]});
  return out;
}

// Throws InputError naming the key and the reason for anything the deck cannot express.
Problem problem(const scene::SceneDef& s) {
  const std::string where = s.file.string() + ": ";
  if (s.contact.law != scene::ContactLaw::potential) {
    throw InputError(where +
                     "contact.law: calculix: the CalculiX peer runs deformable bodies "
                     "(\"potential\"), not " +
                     scene::contact_law_name(s.contact.law));
  }
  Problem p;
  for (std::size_t k = 0; k < s.bodies.size(); ++k) {
    const scene::BodyDef& b = s.bodies[k];
    if (b.fixed) {
      if (p.target >= 0 || std::holds_alternative<scene::MeshShape>(b.shape))
        throw InputError(at_body(s, k) + "calculix: one fixed plane or box only");
      p.target = static_cast<int>(k);
    } else {
      if (p.ball >= 0 || b.model != scene::Model::fem ||
          !std::holds_alternative<scene::MeshShape>(b.shape))
        throw InputError(at_body(s, k) + "calculix: one moving fem body only");
      p.ball = static_cast<int>(k);
    }
  }
  if (p.ball < 0 || p.target < 0)
    throw InputError(where + "bodies: calculix: a moving fem body and a fixed plane or box");
  const auto ball = static_cast<std::size_t>(p.ball);
  const scene::BodyDef& b = s.bodies[ball];
  const auto& mesh = std::get<scene::MeshShape>(b.shape);
  if (!(mesh.element_size > 0))
    throw InputError(at_body(s, ball) +
                     "shape.element_size: calculix: gmsh meshes at the "
                     "scene's element size, which this body does not give");
  if (b.damping_ratio > 0)
    throw InputError(at_body(s, ball) +
                     "damping_ratio: calculix: not mapped (the deck is "
                     "undamped)");
  const double mu = s.contact.friction.value_or(std::min(
      s.materials[static_cast<std::size_t>(b.material)].friction,
      s.materials[static_cast<std::size_t>(s.bodies[static_cast<std::size_t>(p.target)].material)]
          .friction));
  if (mu > 0)
    throw InputError(where + "friction: calculix: frictionless contact only (the friction is " +
                     std::to_string(mu) + ")");
  p.body = body_of(s, ball);
  const scene::BodyDef& t = s.bodies[static_cast<std::size_t>(p.target)];
  const Vec3 v = b.velocity;
  if (const auto* pl = std::get_if<scene::PlaneShape>(&t.shape)) {
    p.plane = {.point = pl->point, .normal = pl->normal.normalized()};
  } else if (const auto* bx = std::get_if<scene::BoxShape>(&t.shape)) {
    // The face the sphere moves towards: the box's face whose outward normal opposes v most.
    int axis = 0;
    for (int i = 1; i < 3; ++i)
      if (std::abs(v[i]) > std::abs(v[axis])) axis = i;
    const double side = v[axis] < 0 ? 1.0 : -1.0;
    p.plane.normal = side * Vec3::Unit(axis);
    p.plane.point = side > 0 ? bx->max : bx->min;
  } else {
    throw InputError(at_body(s, static_cast<std::size_t>(p.target)) +
                     "shape: calculix: the target must be a plane or a box");
  }
  const Vec3 n = p.plane.normal;
  const double speed = -v.dot(n);
  if (!(speed > 0) || (v + speed * n).norm() > kAxisTolerance * speed ||
      b.angular_velocity.norm() > 0) {
    throw InputError(at_body(s, ball) +
                     "velocity: calculix: head-on only (the velocity along the target's normal, "
                     "no spin)");
  }
  const Vec3 axial = p.body.focus.value_or(p.body.centre) - p.body.centre;
  if (p.body.sphere && (axial - axial.dot(n) * n).norm() > kAxisTolerance * p.body.radius + 1e-12) {
    throw InputError(at_body(s, ball) +
                     "shape.element_size_focus: calculix: the focus must lie on the axis of the "
                     "impact (the deck is quarter-symmetric)");
  }
  if ((s.gravity - s.gravity.dot(n) * n).norm() > kAxisTolerance * (s.gravity.norm() + 1))
    throw InputError(where + "gravity: calculix: only along the target's normal");
  return p;
}

void check(const scene::SceneDef& s) {
  (void)problem(s);
}

// Two unit vectors completing n to a right-handed frame.
std::pair<Vec3, Vec3> tangents(const Vec3& n) {
  const Vec3 a = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 e1 = (a - a.dot(n) * n).normalized();
  return {e1, n.cross(e1)};
}

PeerTrace run(const scene::SceneDef& s, const Resolved& r, const fs::path& exe, const fs::path& dir,
              RunMode mode) {
  const fs::path script = ASPERITY_CALCULIX_SCRIPT;
  if (!fs::is_regular_file(script))
    throw PeerFailure("calculix: " + script.string() + ": translator script not found");
  const fs::path gmsh = find_executable("gmsh");
  if (gmsh.empty())
    throw PeerFailure("calculix: gmsh is not installed (the Debian package gmsh meshes the deck)");
  const Problem p = problem(s);
  const Body& body = p.body;
  const scene::BodyDef& b = s.bodies[static_cast<std::size_t>(p.ball)];
  const Material& m = s.materials[static_cast<std::size_t>(b.material)];
  const auto& mesh = std::get<scene::MeshShape>(b.shape);
  const Vec3 n = p.plane.normal;
  const auto [e1, e2] = tangents(n);
  const double radius = body.radius, speed = -b.velocity.dot(n);
  // The strike point: the sphere's pole, or the surface's vertex nearest the plane.
  Vec3 strike = body.centre - radius * n;
  if (!body.sphere) {
    Eigen::Index lowest = 0;
    (body.points.transpose() * n).minCoeff(&lowest);
    strike = body.points.col(lowest);
  }
  const double gap = (strike - p.plane.point).dot(n);
  const Vec3 origin = strike - gap * n;
  const auto frame = [&](const Vec3& x) {
    const Vec3 d = x - origin;
    return Json::array({d.dot(e1), d.dot(e2), d.dot(n)});
  };
  // Hertz's contact time against a rigid plane (Johnson 1985, §11.4), for the step and the end
  // (a particle's: its volume-equivalent sphere's, of the same mass).
  const double e_star = m.young / (1 - m.poisson * m.poisson);
  const double mass = m.density * 4.0 / 3.0 * std::numbers::pi * std::pow(radius, 3);
  const double overlap =
      std::pow(15 * mass * speed * speed / (16 * e_star * std::sqrt(radius)), 0.4);
  const double t_hertz = 2.9432 * overlap / speed;
  const double t_end =
      std::min(r.dt * static_cast<double>(r.steps), std::max(gap, 0.0) / speed + 1.2 * t_hertz);
  // Uniform size (no focus): the sphere's old default, the point under it; a surface's, its strike.
  const Json focus = frame(body.focus.value_or(body.sphere ? origin : strike));
  Json in{{"scene", s.name},
          {"shape", body.sphere ? "sphere" : "surface"},
          {"radius", radius},
          {"length", radius},
          // The slave nodes: the surface within 0.4 R of the plane at the start (R the radius or
          // the equivalent radius), above any approach these impacts reach (1-2 % of R).
          {"slave_height", 0.4 * radius},
          {"gap", gap},
          {"speed", speed},
          {"focus", focus},
          {"size", mesh.element_size},
          {"focus_radius", mesh.element_size_focus ? mesh.element_size_focus_radius : 0.0},
          {"growth", mesh.element_size_focus ? mesh.element_size_growth : 0.0},
          {"far", std::isfinite(mesh.element_size_far) ? mesh.element_size_far : 2 * radius},
          {"law", m.law == ElasticLaw::linear ? "linear" : "neo-hookean"},
          {"young", m.young},
          {"poisson", m.poisson},
          {"density", m.density},
          {"penalty_slope", kPenaltyFactor * m.young / mesh.element_size},
          // ccx's node-to-face tension at large clearances (Pa): 1e-3 of Hertz's peak pressure
          // 3F/(2πa²), a = √(Rδ); the force reads zero to print precision once apart.
          {"sigma_inf", 1e-3 * 2 * e_star * std::sqrt(overlap / radius) / std::numbers::pi},
          {"alpha", -0.05},
          {"dt", t_hertz / kIncrementsPerHertzTime},
          {"increments_per_hertz_time", kIncrementsPerHertzTime},
          {"t_end", t_end},
          {"gravity_z", s.gravity.dot(n)},
          {"gmsh", gmsh.string()},
          {"ccx", exe.string()},
          {"record", s.record.body == p.ball ? "ball" : "plane"},
          {"frame", {{"e1", vec(e1)}, {"e2", vec(e2)}, {"e3", vec(n)}, {"origin", vec(origin)}}}};
  if (!body.sphere) {
    Json points = Json::array(), triangles = Json::array();
    for (Eigen::Index i = 0; i < body.points.cols(); ++i)
      points.push_back(frame(body.points.col(i)));
    for (const auto& t : body.triangles) triangles.push_back({t[0], t[1], t[2]});
    in["points"] = std::move(points);
    in["triangles"] = std::move(triangles);
  }
  write_file(dir / "input.json", in.dump(2) + "\n");
  run_translator("calculix", "python3 " + shell_quote(script.string()), dir);
  const Json raw = Json::parse(std::ifstream(dir / "raw.json"));
  PeerTrace tr;
  if (mode == RunMode::trace) {
    tr = read_trace_csv(dir / "raw.csv", 1, "calculix", true);
    const Json& w = raw.at("spin");  // the sphere's zero by symmetry
    tr.final_w.emplace_back(w[0].get<double>(), w[1].get<double>(), w[2].get<double>());
  }
  tr.cpu_seconds = raw.at("cpu_seconds").get<double>();
  tr.wall_seconds = raw.at("wall_seconds").get<double>();
  tr.version = raw.value("ccx_version", "");
  // ccx's own increments replace asperity's step in the summary.
  tr.extra["dt"] = in.at("dt");
  tr.extra["steps"] = raw.at("increments");
  tr.extra["calculix_increments_per_hertz_time"] = in.at("increments_per_hertz_time");
  for (const char* k : {"nodes", "tets", "symmetry", "meshed_mass", "slave_nodes"})
    tr.extra[std::string("calculix_") + k] = raw.at(k);
  return tr;
}

}  // namespace

Adapter calculix_adapter() {
  return {.name = "calculix",
          .program = "ccx",
          .package = "calculix-ccx",
          .cpu_note = "ccx's process (meshing by gmsh apart), the same run that is traced",
          .check = check,
          .run = run,
          .own_step = true};
}

}  // namespace asperity::peers
