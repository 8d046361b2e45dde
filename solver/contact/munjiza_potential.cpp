// Munjiza's distributed-potential contact of two tetrahedra: clipping and exact integration.
#include "solver/contact/munjiza_potential.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>

namespace asperity::contact {
namespace {

// A triangle clipped by at most 7 planes has at most 10 vertices.
constexpr int kMaxVertices = 12;

// A polygon vertex: position, the four linear functions the clipping tests (barycentric
// coordinates of the other element) and up to four carried linear values.
struct Vertex {
  Vec3 x;
  double l[4];
  double aux[4];
};
struct Polygon {
  int n = 0;
  Vertex v[kMaxVertices];
};

// Barycentric map of an element: L_{1..3} = B (x − x₀), L₀ = 1 − ΣL (TetFrame, the header).
using BaryMap = TetFrame;

// Sutherland–Hodgman: the part of `in` where s(v) ≥ 0, s linear along edges. Returns `in` itself
// when every vertex is kept (the clip would copy it unchanged), else `out` holding the result
// (empty when fewer than 3 vertices remain); each s(v) is evaluated once.
template <class S>
const Polygon* clip(const Polygon& in, Polygon& out, S s) {
  double sv[kMaxVertices];
  bool all_in = true;
  for (int i = 0; i < in.n; ++i) {
    sv[i] = s(in.v[i]);
    all_in = all_in && sv[i] >= 0;
  }
  if (all_in) return &in;
  out.n = 0;
  int p = in.n - 1;
  for (int i = 0; i < in.n; ++i) {
    const Vertex &vp = in.v[p], &q = in.v[i];
    const double sp = sv[p], sq = sv[i];
    if ((sp >= 0) != (sq >= 0)) {
      const double t = sp / (sp - sq);
      Vertex& c = out.v[out.n++];
      c.x = vp.x + t * (q.x - vp.x);
      for (int k = 0; k < 4; ++k) {
        c.l[k] = vp.l[k] + t * (q.l[k] - vp.l[k]);
        c.aux[k] = vp.aux[k] + t * (q.aux[k] - vp.aux[k]);
      }
    }
    if (sq >= 0) out.v[out.n++] = q;
    p = i;
  }
  if (out.n < 3) out.n = 0;
  return &out;
}

// The scratch polygon of `a` and `b` that is not `busy`.
Polygon* other_than(const Polygon* busy, Polygon& a, Polygon& b) {
  return busy == &a ? &b : &a;
}

// Outward faces: the face opposite node m, ordered so that its normal points out of a
// positive-volume element.
constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

// Internal faces of the centroid split: edge (i, j) + centroid, separating the sub-tetrahedra
// opposite m and m2 (the two nodes not on the edge).
constexpr int kInner[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2},
                              {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};

// True when every vertex of the triangle lies beyond one face plane of the element whose
// barycentric coordinates it carries (L_m < 0 at all three): no part of it is inside.
bool beyond_one_face(const Polygon& tri) {
  bool outside = false;
  for (int m = 0; m < 4 && !outside; ++m) {
    outside = tri.v[0].l[m] < 0 && tri.v[1].l[m] < 0 && tri.v[2].l[m] < 0;
  }
  return outside;
}

// The part of `in` inside the element whose barycentrics it carries (L_m ≥ 0 for every m): `in`
// itself or one of the scratch polygons `a`, `b`.
const Polygon* clip_to_element(const Polygon& in, Polygon& a, Polygon& b) {
  const Polygon* p = &in;
  for (int m = 0; m < 4 && p->n > 0; ++m) {
    p = clip(*p, *other_than(p, a, b), [m](const Vertex& v) { return v.l[m]; });
  }
  return p;
}

// The energy terms of t's internal faces (the centroid split) inside c: each face between
// sub-tetrahedra m and m2 adds ∮ φ² g·n dS to m and takes it from m2 (clipping functions: c's
// barycentrics).
void inner_faces_energy(const TetNodes& t, const BaryMap& cm, const BaryMap& tm,
                        double (&energy_sum)[4]) {
  Polygon tri, scratch_a, scratch_b;
  const Vec3 centroid = 0.25 * (t[0] + t[1] + t[2] + t[3]);
  for (const auto& e : kInner) {
    const int i = e[0], j = e[1], m = e[2], m2 = e[3];
    const Vec3 d = tm.grad[m] - tm.grad[m2];  // points out of sub-tetrahedron m
    const double dn = d.norm();
    if (!(dn > 0)) continue;
    const Vec3 n = d / dn;
    tri.n = 3;
    const Vec3 pts[3] = {t[i], t[j], centroid};
    const double phis[3] = {0, 0, 1};
    for (int k = 0; k < 3; ++k) {
      tri.v[k].x = pts[k];
      coords(cm, pts[k], tri.v[k].l);
      tri.v[k].aux[0] = phis[k];
      tri.v[k].aux[1] = tri.v[k].aux[2] = tri.v[k].aux[3] = 0;
    }
    if (beyond_one_face(tri)) continue;
    const Polygon& inside = *clip_to_element(tri, scratch_a, scratch_b);  // inside c
    double i_phi2 = 0;
    for (int k = 1; k + 1 < inside.n; ++k) {
      const Vertex &v0 = inside.v[0], &v1 = inside.v[k], &v2 = inside.v[k + 1];
      const double a = std::abs(0.5 * (v1.x - v0.x).cross(v2.x - v0.x).dot(n));
      const double p0 = v0.aux[0], p1 = v1.aux[0], p2 = v2.aux[0];
      const double sp = p0 + p1 + p2;
      i_phi2 += a / 12.0 * (p0 * p0 + p1 * p1 + p2 * p2 + sp * sp);
    }
    energy_sum[m] += i_phi2 * 4.0 * tm.grad[m].dot(n);
    energy_sum[m2] -= i_phi2 * 4.0 * tm.grad[m2].dot(n);
  }
}

// Barycentric coordinates in one element of the other's four nodes: [node][m].
using NodeCoords = std::array<std::array<double, 4>, 4>;

NodeCoords node_coords(const TetNodes& c, const BaryMap& tm) {
  NodeCoords l;
  for (int k = 0; k < 4; ++k) coords(tm, c[k], l[k].data());
  return l;
}

// True when all four nodes of c lie beyond one face plane of t (L_m < 0 at each): a separating
// plane, so the elements are disjoint and the pair adds nothing. Exact where the box test is
// not: two boxes overlap long before the tetrahedra do (a thin sliver's box is mostly empty).
bool separated(const NodeCoords& c_in_t) {
  for (int m = 0; m < 4; ++m) {
    if (c_in_t[0][m] < 0 && c_in_t[1][m] < 0 && c_in_t[2][m] < 0 && c_in_t[3][m] < 0) return true;
  }
  return false;
}

// One direction: the faces of contactor c are clipped against the sub-tetrahedra of target t;
// forces to fc (on c's nodes) and ft (on t's nodes); returns U_t = p ∫_{c∩t} φ_t dV if asked.
// `c_in_t`: the barycentric coordinates in t of c's four nodes.
double one_way(const TetNodes& c, const BaryMap& cm, const NodeCoords& c_in_t, const TetNodes& t,
               const BaryMap& tm, double penalty, bool with_energy, std::array<Vec3, 4>& fc,
               std::array<Vec3, 4>& ft, double& depth, Vec3& phi_x, double& phi_w) {
  double energy_sum[4] = {0, 0, 0, 0};  // Σ ∮ φ² g_m·n dS per sub-tetrahedron m of t
  double gn[4];
  for (int m = 0; m < 4; ++m) gn[m] = tm.grad[m].norm();
  Polygon tri, scratch_a, scratch_b, sub_a, sub_b;
  for (int f = 0; f < 4; ++f) {
    const int* fn = kFace[f];
    const Vec3 area_vec = 0.5 * (c[fn[1]] - c[fn[0]]).cross(c[fn[2]] - c[fn[0]]);
    const double area = area_vec.norm();
    if (!(area > 0)) continue;
    const Vec3 normal = area_vec / area;
    tri.n = 3;
    for (int k = 0; k < 3; ++k) {
      Vertex& v = tri.v[k];
      v.x = c[fn[k]];
      for (int j = 0; j < 4; ++j) v.l[j] = c_in_t[fn[k]][j];
      v.aux[0] = k == 0, v.aux[1] = k == 1, v.aux[2] = k == 2, v.aux[3] = 0;
    }
    if (beyond_one_face(tri)) continue;                                   // quick reject
    const Polygon& inside = *clip_to_element(tri, scratch_a, scratch_b);  // inside t
    if (inside.n == 0) continue;
    double phi_n[3] = {0, 0, 0}, phi_l[4] = {0, 0, 0, 0};
    for (int m = 0; m < 4; ++m) {
      // Sub-tetrahedron m: L_k − L_m ≥ 0 for k ≠ m.
      const Polygon* src = &inside;
      for (int k = 0; k < 4 && src->n > 0; ++k) {
        if (k == m) continue;
        src = clip(*src, *other_than(src, sub_a, sub_b),
                   [k, m](const Vertex& v) { return v.l[k] - v.l[m]; });
      }
      const Polygon& q = *src;
      if (q.n == 0) continue;
      double phi[kMaxVertices];
      for (int i = 0; i < q.n; ++i) {
        phi[i] = 4.0 * q.v[i].l[m];
        depth = std::max(depth, q.v[i].l[m] / gn[m]);
      }
      double i_phi = 0, i_phi2 = 0;
      for (int i = 1; i + 1 < q.n; ++i) {
        const Vertex &v0 = q.v[0], &v1 = q.v[i], &v2 = q.v[i + 1];
        const double a = 0.5 * (v1.x - v0.x).cross(v2.x - v0.x).dot(normal);
        const double p0 = phi[0], p1 = phi[i], p2 = phi[i + 1];
        const double sp = p0 + p1 + p2;
        const double w = a / 12.0;
        i_phi += a * sp / 3.0;
        i_phi2 += w * (p0 * p0 + p1 * p1 + p2 * p2 + sp * sp);
        for (int k = 0; k < 3; ++k) {
          phi_n[k] += w * (p0 * v0.aux[k] + p1 * v1.aux[k] + p2 * v2.aux[k] +
                           sp * (v0.aux[k] + v1.aux[k] + v2.aux[k]));
        }
        for (int k = 0; k < 4; ++k) {
          phi_l[k] +=
              w * (p0 * v0.l[k] + p1 * v1.l[k] + p2 * v2.l[k] + sp * (v0.l[k] + v1.l[k] + v2.l[k]));
        }
        phi_x += w * (p0 * v0.x + p1 * v1.x + p2 * v2.x + sp * (v0.x + v1.x + v2.x));
      }
      phi_w += i_phi;
      if (with_energy) energy_sum[m] += i_phi2 * 4.0 * tm.grad[m].dot(normal);
    }
    // Traction −p φ n on c's face; the reaction on t.
    const Vec3 f_face = -penalty * normal;
    for (int k = 0; k < 3; ++k) fc[fn[k]] += phi_n[k] * f_face;
    for (int k = 0; k < 4; ++k) ft[k] -= phi_l[k] * f_face;
  }
  if (!with_energy) return 0;

  inner_faces_energy(t, cm, tm, energy_sum);
  double u = 0;
  // g_m = 4 ∇L_m: ∫ φ dV = Σ φ² g·n / (2 |g|²).
  for (int m = 0; m < 4; ++m) u += energy_sum[m] / (2.0 * 16.0 * gn[m] * gn[m]);
  return penalty * u;
}

}  // namespace

TetFrame tet_frame(const TetNodes& t) {
  TetFrame m;
  m.origin = t[0];
  Mat3 d;
  d << t[1] - t[0], t[2] - t[0], t[3] - t[0];
  m.b = d.inverse();
  for (int k = 0; k < 3; ++k) m.grad[k + 1] = m.b.row(k).transpose();
  m.grad[0] = -(m.grad[1] + m.grad[2] + m.grad[3]);
  return m;
}

Eigen::Vector4d barycentric(const TetNodes& t, const Vec3& x) {
  Eigen::Vector4d l;
  coords(tet_frame(t), x, l.data());
  return l;
}

PotentialPairForce munjiza_potential(const TetNodes& a, const TetNodes& b, double penalty,
                                     bool with_energy) {
  return munjiza_potential(a, tet_frame(a), b, tet_frame(b), penalty, with_energy);
}

PotentialPairForce munjiza_potential(const TetNodes& a, const TetFrame& am, const TetNodes& b,
                                     const TetFrame& bm, double penalty, bool with_energy) {
  PotentialPairForce out;
  // Each element's nodes in the other's coordinates: the separating-plane test, then the face
  // vertices of both passes (the same numbers the passes computed face by face before).
  const NodeCoords a_in_b = node_coords(a, bm);
  if (separated(a_in_b)) return out;
  const NodeCoords b_in_a = node_coords(b, am);
  if (separated(b_in_a)) return out;
  Vec3 phi_x = Vec3::Zero();
  double phi_w = 0;
  out.energy = one_way(a, am, a_in_b, b, bm, penalty, with_energy, out.on_a, out.on_b, out.depth,
                       phi_x, phi_w);
  out.energy += one_way(b, bm, b_in_a, a, am, penalty, with_energy, out.on_b, out.on_a, out.depth,
                        phi_x, phi_w);
  if (phi_w > 0) {
    out.weight = phi_w;
    out.point = phi_x / phi_w;
  }
  return out;
}

}  // namespace asperity::contact
