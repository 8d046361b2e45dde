// Building an FEM/DEM world (make_world): bodies and masses → surface tetrahedra and faces →
// penalty and face stiffness → skin → the first candidate pairs and forces.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "solver/contact/volume_hertz.hpp"
#include "solver/core/error.hpp"
#include "solver/fdem/contact_step.hpp"
#include "solver/fdem/world_phases.hpp"

namespace asperity::fdem {
namespace {

double tet_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).cross(c - a).dot(d - a) / 6.0;
}

// Mass, centre and inertia about the centre of a uniform tetrahedral mesh, exact:
// ∫ x xᵀ dV over a tetrahedron = V/20 (Σ xᵢxᵢᵀ + (Σxᵢ)(Σxᵢ)ᵀ) (Tonon 2004, eq. 2 in matrix form).
void mass_properties(const TetMesh& m, double density, double& mass, Vec3& centre, Mat3& inertia) {
  double vol = 0;
  Vec3 first = Vec3::Zero();
  for (Eigen::Index k = 0; k < m.tets.cols(); ++k) {
    const Vec3 a = m.nodes.col(m.tets(0, k)), b = m.nodes.col(m.tets(1, k)),
               c = m.nodes.col(m.tets(2, k)), d = m.nodes.col(m.tets(3, k));
    const double v = tet_volume(a, b, c, d);
    vol += v;
    first += v * 0.25 * (a + b + c + d);
  }
  centre = first / vol;
  Mat3 second = Mat3::Zero();
  for (Eigen::Index k = 0; k < m.tets.cols(); ++k) {
    Vec3 p[4];
    for (int i = 0; i < 4; ++i) p[i] = m.nodes.col(m.tets(i, k)) - centre;
    const double v = tet_volume(p[0], p[1], p[2], p[3]);
    const Vec3 s = p[0] + p[1] + p[2] + p[3];
    Mat3 acc = s * s.transpose();
    for (const Vec3& q : p) acc += q * q.transpose();
    second += v / 20.0 * acc;
  }
  mass = density * vol;
  inertia = density * (second.trace() * Mat3::Identity() - second);
}

// make_world's phases, in the order it calls them.

// Surface faces with their sub-tetrahedron height (centroid to face, 3V/(4A)), for the
// contact time step.
struct Face {
  int body;
  int nodes[3];     // sorted
  int oriented[3];  // as the surface lists it (outward)
  double area, height;
};

// What make_world gathers body by body before it moves it into the world.
struct SurfaceLists {
  std::vector<int> tet_nodes, tet_body;  // surface-adjacent tetrahedra (global nodes), owner
  std::vector<double> tet_height;        // largest sub-tetrahedron height of each
  std::vector<Face> faces;
  std::vector<int> face_owner;   // per face: its tetrahedron among the contact tetrahedra
  std::vector<int> contact_tet;  // the current body's tetrahedra → contact tetrahedron (or −1)
};

void allocate_nodes(World& w, const WorldDef& def) {
  int n_nodes = 0;
  for (const BodyDef& b : def.bodies) n_nodes += static_cast<int>(b.mesh.nodes.cols());
  w.x.resize(3, n_nodes);
  w.v = Eigen::Matrix3Xd::Zero(3, n_nodes);
  w.f = Eigen::Matrix3Xd::Zero(3, n_nodes);
  w.mass.assign(n_nodes, 0.0);
  w.inv_mass.assign(n_nodes, 0.0);
  w.node_body.assign(n_nodes, -1);
}

void check_mesh(const BodyDef& d, const std::string& what) {
  const int nn = static_cast<int>(d.mesh.nodes.cols());
  if (nn < 4 || d.mesh.tets.cols() == 0 || d.mesh.surface.cols() == 0) {
    throw InputError(what + ": mesh has no tetrahedra or no surface");
  }
  if (d.mesh.tets.minCoeff() < 0 || d.mesh.tets.maxCoeff() >= nn || d.mesh.surface.minCoeff() < 0 ||
      d.mesh.surface.maxCoeff() >= nn) {
    throw InputError(what + ": mesh refers to a node that does not exist");
  }
}

// Bodies and masses: the body's nodes at `offset`, their lumped masses, and its elements
// (deformable) or its rigid state (rigid).
Body add_body(World& w, const BodyDef& d, int bi, int offset, const std::string& what) {
  const int nn = static_cast<int>(d.mesh.nodes.cols());
  Body body{.name = d.name,
            .kind = d.kind,
            .node_begin = offset,
            .node_end = offset + nn,
            .material = d.material};
  w.x.middleCols(offset, nn) = d.mesh.nodes;
  for (int i = offset; i < offset + nn; ++i) w.node_body[i] = bi;
  const Eigen::Matrix4Xi tets = d.mesh.tets.array() + offset;
  // Every body's elements give the lumped masses the contact time step uses (a rigid body's
  // too: constraining nodes to move rigidly only lowers the highest frequency).
  fem::TetElements e = fem::make_tet_elements(w.x, tets, d.material.young, d.material.poisson,
                                              d.material.density, 0.0, what);
  // The law is the deformable body's; a rigid or fixed body's elements only give masses and steps,
  // which are the same for both laws (the linear law's stiffness is the neo-Hookean one at F = I).
  if (d.kind == BodyKind::deformable) e.law = d.material.law;
  if (d.kind == BodyKind::deformable && d.damping_ratio > 0) {
    // ξ = β ω / 2 for stiffness-proportional damping, at the body's highest element frequency.
    e.damping = 2 * d.damping_ratio / fem::element_critical_step(e).omega_max;
  }
  std::vector<double> lumped(static_cast<std::size_t>(w.node_count()), 0.0);
  fem::add_lumped_mass(e, lumped);
  Vec3 centre;
  Mat3 inertia;
  mass_properties(d.mesh, d.material.density, body.mass, centre, inertia);
  body.radius = d.kind == BodyKind::fixed
                    ? std::numeric_limits<double>::infinity()
                    : contact::equivalent_radius(body.mass / d.material.density);
  if (d.kind != BodyKind::fixed) {
    for (int i = offset; i < offset + nn; ++i) w.mass[i] = lumped[i];
  }
  if (d.kind == BodyKind::deformable) {
    for (int i = offset; i < offset + nn; ++i) {
      w.inv_mass[i] = 1.0 / w.mass[i];
      w.v.col(i) = d.velocity + d.angular_velocity.cross(w.x.col(i) - centre);
    }
    body.elements = static_cast<int>(w.elements.size());
    w.elements.push_back(std::move(e));
  } else if (d.kind == BodyKind::rigid) {
    RigidBody rb;
    rb.body = bi;
    rb.centre = rb.centre_initial = centre;
    rb.velocity = d.velocity;
    rb.omega = d.angular_velocity;
    rb.mass = body.mass;
    rb.inertia_body = inertia;
    rb.r_body = d.mesh.nodes.colwise() - centre;
    body.rigid = static_cast<int>(w.rigid.size());
    w.rigid.push_back(std::move(rb));
  }
  return body;
}

// Contact tetrahedra: those with a node on the surface (every tetrahedron under a volume law,
// whose overlap integrals clip the surface triangles they own), with their largest
// sub-tetrahedron height.
void add_surface_tets(SurfaceLists& s, const BodyDef& d, int bi, int offset, bool volume_law) {
  s.contact_tet.assign(static_cast<std::size_t>(d.mesh.tets.cols()), -1);
  std::vector<std::uint8_t> on_surface(static_cast<std::size_t>(d.mesh.nodes.cols()), 0);
  for (Eigen::Index k = 0; k < d.mesh.surface.size(); ++k) on_surface[d.mesh.surface.data()[k]] = 1;
  for (Eigen::Index k = 0; k < d.mesh.tets.cols(); ++k) {
    const auto t = d.mesh.tets.col(k);
    if (!(volume_law || on_surface[t[0]] || on_surface[t[1]] || on_surface[t[2]] ||
          on_surface[t[3]])) {
      continue;
    }
    s.contact_tet[static_cast<std::size_t>(k)] = static_cast<int>(s.tet_body.size());
    for (int i = 0; i < 4; ++i) s.tet_nodes.push_back(t[i] + offset);
    s.tet_body.push_back(bi);
    // h_m = 3V/(4 A_m): the largest belongs to the smallest face.
    Vec3 p[4];
    for (int i = 0; i < 4; ++i) p[i] = d.mesh.nodes.col(t[i]);
    double a_min = 1e300;
    for (int skip = 0; skip < 4; ++skip) {
      const Vec3 &q0 = p[(skip + 1) % 4], &q1 = p[(skip + 2) % 4], &q2 = p[(skip + 3) % 4];
      a_min = std::min(a_min, 0.5 * (q1 - q0).cross(q2 - q0).norm());
    }
    s.tet_height.push_back(0.75 * tet_volume(p[0], p[1], p[2], p[3]) / a_min);
  }
}

// Surface faces: each surface triangle with the tetrahedron it bounds (its area and
// sub-tetrahedron height); a triangle that bounds none is an input error.
void add_surface_faces(SurfaceLists& s, const BodyDef& d, int bi, int offset,
                       const std::string& what) {
  std::map<std::array<int, 3>, int> face_tet;
  for (Eigen::Index k = 0; k < d.mesh.tets.cols(); ++k) {
    const auto t = d.mesh.tets.col(k);
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> key{};
      for (int i = 0, j = 0; i < 4; ++i) {
        if (i != skip) key[j++] = t[i];
      }
      std::sort(key.begin(), key.end());
      face_tet[key] = static_cast<int>(k);
    }
  }
  for (Eigen::Index k = 0; k < d.mesh.surface.cols(); ++k) {
    std::array<int, 3> key{d.mesh.surface(0, k), d.mesh.surface(1, k), d.mesh.surface(2, k)};
    std::sort(key.begin(), key.end());
    const auto it = face_tet.find(key);
    if (it == face_tet.end()) {
      throw InputError(what + ": surface triangle " + std::to_string(k) +
                       " is not a face of any tetrahedron");
    }
    const Vec3 a = d.mesh.nodes.col(d.mesh.surface(0, k)),
               b = d.mesh.nodes.col(d.mesh.surface(1, k)),
               c = d.mesh.nodes.col(d.mesh.surface(2, k));
    const double area = 0.5 * (b - a).cross(c - a).norm();
    const auto t = d.mesh.tets.col(it->second);
    const double v = tet_volume(d.mesh.nodes.col(t[0]), d.mesh.nodes.col(t[1]),
                                d.mesh.nodes.col(t[2]), d.mesh.nodes.col(t[3]));
    s.face_owner.push_back(s.contact_tet[static_cast<std::size_t>(it->second)]);
    s.faces.push_back({.body = bi,
                       .nodes = {key[0] + offset, key[1] + offset, key[2] + offset},
                       .oriented = {d.mesh.surface(0, k) + offset, d.mesh.surface(1, k) + offset,
                                    d.mesh.surface(2, k) + offset},
                       .area = area,
                       .height = 0.75 * v / area});
  }
}

// Penalty p (Pa): given, or α times the largest Young's modulus of the bodies that deform or
// move; a fixed block only supplies the target (a stiff steel block must not shrink the step of
// a softer rock particle). With no moving body, the largest of all.
double contact_penalty(const WorldDef& def) {
  if (def.contact.penalty > 0) return def.contact.penalty;
  double young_max = 0;
  for (const BodyDef& d : def.bodies) {
    if (d.kind != BodyKind::fixed) young_max = std::max(young_max, d.material.young);
  }
  if (young_max == 0) {
    for (const BodyDef& d : def.bodies) young_max = std::max(young_max, d.material.young);
  }
  return def.contact.alpha * young_max;
}

// Skin: half the mean sub-tetrahedron height of the moving bodies' surface faces. Rebuilds
// happen every ~skin/(2 v dt) steps; the extra candidates cost one box test each per step.
double contact_skin(const World& w, const std::vector<Face>& faces) {
  double hsum = 0;
  int hn = 0;
  for (const Face& f : faces) {
    if (w.bodies[f.body].kind != BodyKind::fixed) hsum += f.height, ++hn;
  }
  return hn > 0 ? 0.5 * hsum / hn : 0;
}

void set_face_stiffness(World& w, const std::vector<Face>& faces) {
  w.face_nodes.resize(3, static_cast<Eigen::Index>(faces.size()));
  w.face_outward.resize(3, static_cast<Eigen::Index>(faces.size()));
  w.face_stiffness.resize(faces.size());
  std::vector<double> h_min(w.bodies.size(), 1e300);  // smallest height on any other body
  for (const Face& f : faces) {
    for (std::size_t b = 0; b < w.bodies.size(); ++b) {
      if (static_cast<int>(b) != f.body) h_min[b] = std::min(h_min[b], f.height);
    }
  }
  for (std::size_t k = 0; k < faces.size(); ++k) {
    const Face& f = faces[k];
    w.face_nodes.col(static_cast<Eigen::Index>(k)) << f.nodes[0], f.nodes[1], f.nodes[2];
    w.face_outward.col(static_cast<Eigen::Index>(k)) << f.oriented[0], f.oriented[1], f.oriented[2];
    // Stiffness of the face pressed into another body: the overlap A·d sits in this face's
    // sub-tetrahedron and in the other body's, ∇φ = 1/height in each, so dF/dd = p A (1/h + 1/h').
    const double other = h_min[f.body] < 1e299 ? 1.0 / h_min[f.body] : 0.0;
    w.face_stiffness[k] = w.penalty * f.area * (1.0 / f.height + other);
  }
}

// Surface triangles by owning contact tetrahedron (CSR), for the volume laws' clipping.
void index_faces_by_tet(World& w, const std::vector<int>& face_owner) {
  w.tet_faces_begin.assign(w.surface_tet_body.size() + 1, 0);
  for (const int t : face_owner) {
    if (t >= 0) ++w.tet_faces_begin[static_cast<std::size_t>(t) + 1];
  }
  for (std::size_t k = 1; k < w.tet_faces_begin.size(); ++k) {
    w.tet_faces_begin[k] += w.tet_faces_begin[k - 1];
  }
  w.tet_faces.resize(static_cast<std::size_t>(w.tet_faces_begin.back()));
  std::vector<int> fill(w.tet_faces_begin.begin(), w.tet_faces_begin.end() - 1);
  for (std::size_t f = 0; f < face_owner.size(); ++f) {
    const int t = face_owner[f];
    if (t >= 0)
      w.tet_faces[static_cast<std::size_t>(fill[static_cast<std::size_t>(t)]++)] =
          static_cast<int>(f);
  }
}

}  // namespace

// Bodies and masses → surface tetrahedra and faces → penalty and face stiffness → skin → the
// first candidate pairs and forces.
World make_world(const WorldDef& def) {
  World w;
  w.gravity = def.gravity;
  allocate_nodes(w, def);
  SurfaceLists surface;
  int offset = 0;
  const bool volume_law = def.contact.law != ContactLaw::potential;
  for (std::size_t bi = 0; bi < def.bodies.size(); ++bi) {
    const BodyDef& d = def.bodies[bi];
    const std::string what = "body \"" + d.name + "\"";
    const int body = static_cast<int>(bi);
    check_mesh(d, what);
    if (volume_law && d.kind == BodyKind::deformable) {
      throw InputError(what + ": the volume contact laws are for rigid and fixed bodies only");
    }
    w.bodies.push_back(add_body(w, d, body, offset, what));
    add_surface_tets(surface, d, body, offset, volume_law);
    add_surface_faces(surface, d, body, offset, what);
    offset += static_cast<int>(d.mesh.nodes.cols());
  }
  w.surface_tets = Eigen::Map<const Eigen::Matrix4Xi>(
      surface.tet_nodes.data(), 4, static_cast<Eigen::Index>(surface.tet_body.size()));
  w.surface_tet_body = std::move(surface.tet_body);
  w.surface_tet_height = std::move(surface.tet_height);
  w.penalty = contact_penalty(def);
  w.friction = def.contact.friction;
  w.law = def.contact.law;
  w.kv = def.contact.kv;
  w.kt = def.contact.kt;
  if (w.law == ContactLaw::volume_linear && !(w.kv > 0)) {
    throw InputError("contact: volume-linear needs a stiffness kv > 0 (N/m³)");
  }
  index_faces_by_tet(w, surface.face_owner);
  w.skin = contact_skin(w, surface.faces);
  set_face_stiffness(w, surface.faces);
  w.penalty_asked = w.penalty;
  if (w.law == ContactLaw::potential && def.contact.max_contact_factor > 0) {
    w.contact_factor = def.contact.max_contact_factor;
    switch (def.contact.contact_step_fix) {
      case ContactStepFix::penalty:
        limit_penalty(w, def.contact.max_contact_factor);
        break;
      case ContactStepFix::face_penalty:
        limit_face_penalty(w, def.contact.max_contact_factor);
        break;
      case ContactStepFix::mass:
        if (def.contact.max_added_mass > 0) {
          w.contact_factor = scale_contact_mass_within(w, def.contact.max_contact_factor,
                                                       def.contact.max_added_mass);
        } else {
          scale_contact_mass(w, def.contact.max_contact_factor);
        }
        break;
    }
  }

  w.x_initial = w.x;
  detail::rebuild_pairs(w);
  detail::compute_forces(w, 0.0);
  detail::reduce_rigid(w);
  return w;
}

}  // namespace asperity::fdem
