// Predicted critical step of an FEM/DEM world (formulas in time_step.hpp).
#include "solver/fdem/time_step.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>

#include "solver/contact/volume_hertz.hpp"
#include "solver/core/central_difference.hpp"
#include "solver/core/effective_mass.hpp"
#include "solver/fdem/world_phases.hpp"

namespace asperity::fdem {

namespace {

using Key = std::array<int, 3>;

Key sorted_key(int a, int b, int c) {
  Key k{a, b, c};
  std::sort(k.begin(), k.end());
  return k;
}

// Consistent face matrix weight of nodes i, j of a face (×k_f): 2/12 on the diagonal, 1/12 off.
double face_weight(int i, int j) {
  return (i == j ? 2.0 : 1.0) / 12.0;
}

int face_body(const World& w, int f) {
  return w.node_body[w.face_nodes(0, f)];
}

// The part of triangle p where the linear function with vertex values d is ≥ 0 (up to four
// corners, with the function's values there).
struct Polygon {
  Vec3 p[4];
  double d[4];
  int n = 0;
};
Polygon clip_positive(const std::array<Vec3, 3>& p, const std::array<double, 3>& d) {
  Polygon out;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (d[i] >= 0) out.p[out.n] = p[i], out.d[out.n++] = d[i];
    if ((d[i] >= 0) != (d[j] >= 0)) {
      const double s = d[i] / (d[i] - d[j]);
      out.p[out.n] = p[i] + s * (p[j] - p[i]), out.d[out.n++] = 0;
    }
  }
  return out;
}

// ∫ f dV over the part of tetrahedron q where the linear function d ≥ 0, f linear with vertex
// values f: each piece is a tetrahedron, where ∫ f dV = |V| × the mean of f at its corners. One
// vertex in: the corner tetrahedron; three in: the whole minus the corner that is out; two in:
// the wedge between the two cut triangles, three tetrahedra.
double clipped_integral(const std::array<Vec3, 4>& q, const std::array<double, 4>& d,
                        const std::array<double, 4>& f) {
  auto tet = [](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& e, double fa, double fb,
                double fc, double fe) {
    return std::abs((b - a).cross(c - a).dot(e - a)) / 6 * 0.25 * (fa + fb + fc + fe);
  };
  int in[4], out[4], ni = 0, no = 0;
  for (int i = 0; i < 4; ++i) (d[i] >= 0 ? in[ni++] : out[no++]) = i;
  // Point on edge i–j where d = 0, and f there.
  auto cut = [&](int i, int j, Vec3& x, double& fx) {
    const double s = d[i] / (d[i] - d[j]);
    x = q[i] + s * (q[j] - q[i]);
    fx = f[i] + s * (f[j] - f[i]);
  };
  if (ni == 0) return 0;
  if (ni == 4) return tet(q[0], q[1], q[2], q[3], f[0], f[1], f[2], f[3]);
  if (ni == 1 || ni == 3) {
    const bool whole = ni == 3;
    const int a = whole ? out[0] : in[0];
    const int* others = whole ? in : out;
    Vec3 x[3];
    double fx[3];
    for (int k = 0; k < 3; ++k) cut(a, others[k], x[k], fx[k]);
    const double corner = tet(q[a], x[0], x[1], x[2], f[a], fx[0], fx[1], fx[2]);
    return whole ? tet(q[0], q[1], q[2], q[3], f[0], f[1], f[2], f[3]) - corner : corner;
  }
  const int a = in[0], b = in[1], c = out[0], e = out[1];
  Vec3 ac, ae, bc, be;
  double fac, fae, fbc, fbe;
  cut(a, c, ac, fac), cut(a, e, ae, fae), cut(b, c, bc, fbc), cut(b, e, be, fbe);
  // Prism (a, ac, ae) – (b, bc, be).
  return tet(q[a], ac, ae, be, f[a], fac, fae, fbe) + tet(q[a], ac, bc, be, f[a], fac, fbc, fbe) +
         tet(q[a], q[b], bc, be, f[a], f[b], fbc, fbe);
}

bool inside_triangle(const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& n) {
  // Projected along n: q is inside when it is on the same side of all three edges.
  const double s0 = n.dot((b - a).cross(q - a)), s1 = n.dot((c - b).cross(q - b)),
               s2 = n.dot((a - c).cross(q - c));
  const double tol = 1e-12 * (b - a).squaredNorm();
  return (s0 >= -tol && s1 >= -tol && s2 >= -tol) || (s0 <= tol && s1 <= tol && s2 <= tol);
}

// G(x) = [I, −[r]×], r = x − c: the displacement at x under the rigid motion (t, θ).
Eigen::Matrix<double, 3, 6> rigid_map(const Vec3& x, const Vec3& c) {
  const Vec3 r = x - c;
  Eigen::Matrix<double, 3, 6> g;
  g << 1, 0, 0, 0, r.z(), -r.y(), 0, 1, 0, -r.z(), 0, r.x(), 0, 0, 1, r.y(), -r.x(), 0;
  return g;
}

// K_r = Σ_f κ_f ∫_{P_f} G(x)ᵀ G(x) dA, κ_f = k_f / A_f the face's stiffness per area and P_f
// the pressed part of the face (all of it in the fallback, where this is Σ G_fᵀ K_f G_f with the
// consistent face matrix, since u(x) is linear over the face). G is linear in x, so the
// edge-midpoint rule (exact for quadratics) integrates it exactly on each fan triangle.
double rigid_omega2(const World& w, const RigidBody& rb, const ContactFaces& c) {
  Eigen::Matrix<double, 6, 6> k = Eigen::Matrix<double, 6, 6>::Zero(),
                              m = Eigen::Matrix<double, 6, 6>::Zero();
  for (const int f : c.faces) {
    std::array<Vec3, 3> p;
    std::array<double, 3> d;
    for (int i = 0; i < 3; ++i) {
      p[i] = w.x.col(w.face_nodes(i, f));
      d[i] = c.depth < 0 ? 1.0 : c.depth - (c.support - p[i].dot(c.normal));
    }
    const double area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    if (!(area > 0)) continue;
    const double kappa = w.face_stiffness[f] / area;
    const Polygon poly = clip_positive(p, d);
    for (int t = 1; t + 1 < poly.n; ++t) {
      const Vec3 q[3] = {poly.p[0], poly.p[t], poly.p[t + 1]};
      const double a = 0.5 * (q[1] - q[0]).cross(q[2] - q[0]).norm();
      for (int e = 0; e < 3; ++e) {
        const Eigen::Matrix<double, 3, 6> g = rigid_map(0.5 * (q[e] + q[(e + 1) % 3]), rb.centre);
        k += kappa * a / 3 * g.transpose() * g;
      }
    }
  }
  const Mat3 rot = rb.orientation.toRotationMatrix();
  m.topLeftCorner<3, 3>() = rb.mass * Mat3::Identity();
  m.bottomRightCorner<3, 3>() = rot * rb.inertia_body * rot.transpose();
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> es(
      k, m, Eigen::EigenvaluesOnly);
  return std::max(0.0, es.eigenvalues().maxCoeff());
}

double damped_step(double omega, double beta) {
  return damped_critical_step(omega, 0.5 * beta * omega);  // ξ = β ω / 2 (Kelvin–Voigt)
}

}  // namespace

namespace detail {

// The penalty spring of every surface face of deformable body `body`, as extra stiffness of the
// element that owns the face.
std::vector<fem::ElementExtraStiffness> face_springs(const World& w, int body,
                                                     const std::vector<double>* face_scale) {
  const fem::TetElements& e = w.elements[w.bodies[body].elements];
  std::map<Key, std::pair<int, int>> owner;  // face → (element, the local node left out)
  for (int t = 0; t < e.size(); ++t) {
    for (int skip = 0; skip < 4; ++skip) {
      int n[3], j = 0;
      for (int a = 0; a < 4; ++a) {
        if (a != skip) n[j++] = e.tets(a, t);
      }
      owner[sorted_key(n[0], n[1], n[2])] = {t, skip};
    }
  }
  std::vector<fem::ElementExtraStiffness> out;
  for (Eigen::Index f = 0; f < w.face_nodes.cols(); ++f) {
    if (face_body(w, static_cast<int>(f)) != body) continue;
    const auto it =
        owner.find(sorted_key(w.face_nodes(0, f), w.face_nodes(1, f), w.face_nodes(2, f)));
    if (it == owner.end()) continue;  // make_world checked that every face has its element
    const int t = it->second.first;
    fem::ElementExtraStiffness x{.element = t, .k = Eigen::Matrix<double, 12, 12>::Zero()};
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) {
        if (a == it->second.second || b == it->second.second) continue;
        const double k =
            w.face_stiffness[f] * (face_scale ? (*face_scale)[static_cast<std::size_t>(f)] : 1.0);
        x.k.block<3, 3>(3 * a, 3 * b) = k * face_weight(a, b) * Mat3::Identity();
      }
    }
    out.push_back(x);
  }
  return out;
}

}  // namespace detail

using detail::face_springs;

ContactFaces rigid_contact_faces(const World& w, int rigid) {
  const RigidBody& rb = w.rigid[rigid];
  ContactFaces all;
  for (Eigen::Index f = 0; f < w.face_nodes.cols(); ++f) {
    if (face_body(w, static_cast<int>(f)) == rb.body) all.faces.push_back(static_cast<int>(f));
  }
  for (std::size_t b = 0; b < w.bodies.size(); ++b) {
    if (static_cast<int>(b) != rb.body && w.bodies[b].kind != BodyKind::fixed) return all;
  }
  const Vec3 v = rb.velocity, g = w.gravity;
  if (rb.omega.norm() > 0) return all;
  Vec3 n;
  if (v.norm() > 0) {
    n = v.normalized();
    if (g.cross(n).norm() > 1e-9 * g.norm() || g.dot(n) < 0) return all;
  } else if (g.norm() > 0) {
    n = g.normalized();
  } else {
    return all;
  }
  const Body& body = w.bodies[rb.body];
  double z_support = -std::numeric_limits<double>::infinity(), extent = 0;
  for (int i = body.node_begin; i < body.node_end; ++i) {
    z_support = std::max(z_support, w.x.col(i).dot(n));
  }
  for (int i = body.node_begin; i < body.node_end; ++i) {
    extent = std::max(extent, z_support - w.x.col(i).dot(n));
  }
  // The target plane: the fixed nodes nearest along n, and the fixed faces lying in it.
  double z_target = std::numeric_limits<double>::infinity();
  for (int i = 0; i < w.node_count(); ++i) {
    if (w.bodies[w.node_body[i]].kind == BodyKind::fixed) {
      z_target = std::min(z_target, w.x.col(i).dot(n));
    }
  }
  const double gap = z_target - z_support;
  if (!(gap >= 0) || !(extent > 0)) return all;
  const double tol = 1e-9 * extent;
  std::vector<int> target_faces;
  for (Eigen::Index f = 0; f < w.face_nodes.cols(); ++f) {
    if (w.bodies[face_body(w, static_cast<int>(f))].kind != BodyKind::fixed) continue;
    bool flat = true;
    for (int i = 0; i < 3; ++i) flat = flat && w.x.col(w.face_nodes(i, f)).dot(n) <= z_target + tol;
    if (flat) target_faces.push_back(static_cast<int>(f));
  }
  // Stored-energy lower bound at penetration δ: p ∫ φ_a dV over the body's surface-adjacent
  // tetrahedra beyond the target plane, φ_a linear on each of the four sub-tetrahedra (0 on the
  // face, 1 at the centroid).
  std::vector<std::array<Vec3, 4>> tets;
  for (Eigen::Index t = 0; t < w.surface_tets.cols(); ++t) {
    if (w.surface_tet_body[t] != rb.body) continue;
    std::array<Vec3, 4> q;
    for (int a = 0; a < 4; ++a) q[a] = w.x.col(w.surface_tets(a, t));
    tets.push_back(q);
  }
  const double energy_in = 0.5 * rb.mass * v.squaredNorm();
  const double gn = std::max(0.0, g.dot(n));
  auto excess = [&](double delta) {  // stored-energy lower bound minus the energy available
    double u = 0;
    for (const std::array<Vec3, 4>& q : tets) {
      const Vec3 centroid = 0.25 * (q[0] + q[1] + q[2] + q[3]);
      for (int m = 0; m < 4; ++m) {
        std::array<Vec3, 4> sub = q;
        sub[m] = centroid;
        std::array<double, 4> d, f{0, 0, 0, 0};
        f[m] = 1;
        for (int i = 0; i < 4; ++i) d[i] = delta - (z_support - sub[i].dot(n));
        u += w.penalty * clipped_integral(sub, d, f);
      }
    }
    return u - energy_in - rb.mass * gn * (gap + delta);
  };
  double hi = 1e-9 * extent;
  while (excess(hi) < 0) {
    hi *= 2;
    if (hi > extent) return all;  // no bound short of burying the body: count every face
  }
  double lo = 0;
  for (int it = 0; it < 100 && hi - lo > 1e-12 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (excess(mid) < 0 ? lo : hi) = mid;
  }
  ContactFaces out;
  out.depth = hi;
  out.normal = n;
  out.support = z_support;
  for (const int f : all.faces) {
    bool touches = false;
    for (int i = 0; i < 3; ++i) {
      const Vec3 p = w.x.col(w.face_nodes(i, f));
      if (z_support - p.dot(n) > out.depth) continue;
      touches = true;
      // The patch that can touch must lie over the target's flat face.
      bool over = false;
      for (const int tf : target_faces) {
        over =
            over || inside_triangle(p, w.x.col(w.face_nodes(0, tf)), w.x.col(w.face_nodes(1, tf)),
                                    w.x.col(w.face_nodes(2, tf)), n);
      }
      if (!over) return all;
    }
    if (touches) out.faces.push_back(f);
  }
  return out;
}

// Volume laws (contact/volume_hertz.hpp, contact/volume_linear.hpp): each moving rigid body
// against every other body, as an oscillator of its effective mass on the law's stiffness at the
// peak of the hardest impact the scene allows. The effective mass at a contact point r from the
// centre is 1/(1/m + |r|²/I_min) at most (a push off the centre line also spins the body), with
// |r| the body's largest node distance. The approach speed v is bounded by both bodies' speeds
// plus spin times reach, plus the fall √(2|g|H) over the scene's height H along gravity.
//   volume-hertz: the Hertz pair with the law's R* and E* (it is Hertz for spheres), stiffness
//     dF/dδ = 2 E* √(R* δ_max) at δ_max = (15 m v² / (16 E* √R*))^{2/5} (Johnson 1985, §11.4).
//     A flat face striking a plane has F ∝ δ^{1/4}, whose tangent stiffness is unbounded at the
//     first touch where the force is still near zero; no finite bound covers it, so the
//     Hertz step stands and the face impact is checked by its energy (tests/fdem/
//     test_volume_contact.cpp).
//   volume-linear: F = k_v V ≤ k_v A δ with A ≤ half the body's surface area (no cross-section of
//     a convex body exceeds it), so the stiffness is at most k_v A.
namespace {
CriticalStep volume_critical_step(const World& w) {
  CriticalStep out;
  const double inf = std::numeric_limits<double>::infinity();
  out.element = out.contact = out.critical = inf;
  const double g = w.gravity.norm();
  double height = 0;
  if (g > 0) {
    const Eigen::RowVectorXd along = (w.gravity / g).transpose() * w.x;
    height = along.maxCoeff() - along.minCoeff();
  }
  const double fall = std::sqrt(2 * g * height);
  std::vector<double> reach(w.bodies.size(), 0.0), surface(w.bodies.size(), 0.0),
      speed(w.bodies.size(), 0.0), mass_eff(w.bodies.size(), inf);
  for (const RigidBody& rb : w.rigid) {
    const auto b = static_cast<std::size_t>(rb.body);
    reach[b] = rb.r_body.colwise().norm().maxCoeff();
    const double i_min = Eigen::SelfAdjointEigenSolver<Mat3>(rb.inertia_body).eigenvalues()[0];
    mass_eff[b] = 1.0 / (1.0 / rb.mass + reach[b] * reach[b] / i_min);
    speed[b] = rb.velocity.norm() + rb.omega.norm() * reach[b];
  }
  for (Eigen::Index f = 0; f < w.face_nodes.cols(); ++f) {
    const Vec3 a = w.x.col(w.face_nodes(0, f)), b = w.x.col(w.face_nodes(1, f)),
               c = w.x.col(w.face_nodes(2, f));
    surface[static_cast<std::size_t>(w.node_body[w.face_nodes(0, f)])] +=
        0.5 * (b - a).cross(c - a).norm();
  }
  // Largest flat patch of each moving body: its surface triangles grouped by plane (unit normal
  // and offset rounded to 1e-6 of the body's reach), areas summed.
  std::vector<double> flat(w.bodies.size(), 0.0);
  {
    std::map<std::array<long long, 5>, double> patches;
    for (Eigen::Index f = 0; f < w.face_nodes.cols(); ++f) {
      const auto b = static_cast<std::size_t>(w.node_body[w.face_nodes(0, f)]);
      if (w.bodies[b].kind != BodyKind::rigid) continue;
      const Vec3 a = w.x.col(w.face_nodes(0, f)), p = w.x.col(w.face_nodes(1, f)),
                 c = w.x.col(w.face_nodes(2, f));
      const Vec3 n2 = (p - a).cross(c - a);
      const double area2 = n2.norm();
      if (!(area2 > 0)) continue;
      Vec3 n = n2 / area2;
      // Either orientation of the same plane is the same patch.
      if (n.x() < 0 || (n.x() == 0 && (n.y() < 0 || (n.y() == 0 && n.z() < 0)))) n = -n;
      const double q = 1e6;
      const auto key = std::array<long long, 5>{static_cast<long long>(b), std::llround(n.x() * q),
                                                std::llround(n.y() * q), std::llround(n.z() * q),
                                                std::llround(n.dot(a) / reach[b] * q)};
      patches[key] += 0.5 * area2;
    }
    for (const auto& [key, area] : patches) {
      const auto b = static_cast<std::size_t>(key[0]);
      flat[b] = std::max(flat[b], area);
    }
  }
  double omega_max = 0;
  for (const RigidBody& rb : w.rigid) {
    const auto i = static_cast<std::size_t>(rb.body);
    for (std::size_t j = 0; j < w.bodies.size(); ++j) {
      if (j == i) continue;
      const Body &bi = w.bodies[i], &bj = w.bodies[j];
      const double m = effective_mass(mass_eff[i], mass_eff[j]);
      const double v = speed[i] + speed[j] + fall;
      double k = 0;
      if (w.law == ContactLaw::volume_hertz) {
        const double e = effective_young(bi.material, bj.material);
        const double r = contact::volume_hertz_radius(bi.radius, bj.radius);
        const double delta = std::pow(15.0 * m * v * v / (16.0 * e * std::sqrt(r)), 0.4);
        k = 2.0 * e * std::sqrt(r * delta);
        // A flat face of area A pressed into a flat target: V = A δ, W = c (A δ)^{5/4}, so the
        // deepest approach is δ_f = (m v² / 2c)^{4/5} / A and the contact lasts more than
        // 2 δ_f / v; its step is taken as δ_f / v, as the Hertz step 2/ω is about half the Hertz
        // duration. A is the body's largest flat patch (the smaller of the two for two moving
        // bodies: no overlap's cross-section exceeds either).
        const double area = bj.kind == BodyKind::rigid ? std::min(flat[i], flat[j]) : flat[i];
        if (area > 0) {
          const double c = contact::volume_hertz_coefficient(e, r);
          const double delta_f = std::pow(m * v * v / (2.0 * c), 0.8) / area;
          // As an ω: the step 2/ω equals δ_f / v.
          omega_max = std::max(omega_max, 2.0 * v / delta_f);
        }
      } else {
        const double area =
            0.5 * (bj.kind == BodyKind::rigid ? std::min(surface[i], surface[j]) : surface[i]);
        k = w.kv * area;
      }
      omega_max = std::max(omega_max, std::sqrt(k / m));
    }
  }
  if (omega_max > 0) out.contact = out.critical = 2.0 / omega_max;
  out.limited_by = "contact";
  return out;
}
}  // namespace

CriticalStep critical_step(const World& w) {
  if (w.law != ContactLaw::potential) return volume_critical_step(w);
  CriticalStep out;
  const double inf = std::numeric_limits<double>::infinity();
  out.element = out.contact = out.critical = inf;
  std::vector<double> k_row(w.node_count(), 0.0);
  for (Eigen::Index f = 0; f < w.face_nodes.cols(); ++f) {
    for (int i = 0; i < 3; ++i) k_row[w.face_nodes(i, f)] += w.face_stiffness[f] / 3.0;
  }
  double omega_e_max = 0, omega_c2 = 0;
  for (std::size_t b = 0; b < w.bodies.size(); ++b) {
    const Body& body = w.bodies[b];
    if (body.kind != BodyKind::deformable) continue;
    const fem::TetElements& e = w.elements[body.elements];
    const fem::ElementStep elem = fem::element_critical_step(e, {}, w.added_mass);
    double gershgorin = 0;  // Σ (k_f/3) / m over the body's nodes
    for (int i = body.node_begin; i < body.node_end; ++i) {
      if (w.mass[i] > 0) gershgorin = std::max(gershgorin, k_row[i] / w.mass[i]);
    }
    const double weyl2 = elem.omega_max * elem.omega_max + gershgorin;
    const fem::ElementStep both =
        fem::element_critical_step(e, face_springs(w, static_cast<int>(b)), w.added_mass);
    const double omega = std::sqrt(std::min(weyl2, both.omega_max * both.omega_max));
    if (elem.omega_max > omega_e_max) {
      omega_e_max = elem.omega_max;
      out.element_body = body.name;
    }
    out.element = std::min(out.element, elem.dt);
    omega_c2 = std::max(omega_c2, gershgorin);
    out.critical = std::min(out.critical, damped_step(omega, e.damping));
  }
  for (int r = 0; r < static_cast<int>(w.rigid.size()); ++r) {
    const ContactFaces faces = rigid_contact_faces(w, r);
    const double omega2 = rigid_omega2(w, w.rigid[r], faces);
    omega_c2 = std::max(omega_c2, omega2);
    out.critical = std::min(out.critical, damped_step(std::sqrt(omega2), 0));
  }
  if (omega_c2 > 0) out.contact = 2.0 / std::sqrt(omega_c2);
  out.limited_by = out.element <= out.contact ? "element" : "contact";
  return out;
}

}  // namespace asperity::fdem
