// Overlap of two polyhedra: a surface triangle of one body clipped by a tetrahedron of the other,
// integrated exactly (contact/overlap_volume.hpp).
#include "solver/contact/overlap_volume.hpp"

#include <Eigen/Geometry>

namespace asperity::contact {
namespace {

// A triangle clipped by 4 planes keeps at most 3 + 4 vertices.
constexpr int kMaxVertices = 8;

struct Poly {
  int n = 0;
  Vec3 x[kMaxVertices];
  double s[kMaxVertices];  // the signed distance-like value of the current clipping plane
};

// Keeps the part of `in` where the linear function `plane` (a·x + d) is ≥ 0.
void clip(const Poly& in, Poly& out, const Vec3& a, double d) {
  out.n = 0;
  if (in.n == 0) return;
  double sp = a.dot(in.x[in.n - 1]) + d;
  const Vec3* p = &in.x[in.n - 1];
  for (int i = 0; i < in.n; ++i) {
    const Vec3& q = in.x[i];
    const double sq = a.dot(q) + d;
    if ((sp >= 0) != (sq >= 0)) out.x[out.n++] = *p + (sp / (sp - sq)) * (q - *p);
    if (sq >= 0) out.x[out.n++] = q;
    p = &q;
    sp = sq;
  }
  if (out.n < 3) out.n = 0;
}

}  // namespace

bool clip_triangle_in_tet(const Triangle& tri, const TetNodes& tet, const Vec3& origin,
                          OverlapSide& side) {
  // Inward face planes of the tetrahedron: for the face opposite node m, a·x + d ≥ 0 on m's side
  // (a = (x_j − x_i) × (x_k − x_i) oriented towards m; only the sign matters, not the scale).
  Poly p, q;
  p.n = 3;
  for (int k = 0; k < 3; ++k) p.x[k] = tri[k] - origin;
  Poly* src = &p;
  Poly* dst = &q;
  for (int m = 0; m < 4; ++m) {
    const Vec3 x0 = tet[(m + 1) % 4] - origin, x1 = tet[(m + 2) % 4] - origin,
               x2 = tet[(m + 3) % 4] - origin, xm = tet[m] - origin;
    Vec3 a = (x1 - x0).cross(x2 - x0);
    double d = -a.dot(x0);
    if (a.dot(xm) + d < 0) a = -a, d = -d;
    // Quick reject: every vertex strictly outside this face plane.
    bool outside = true;
    for (int k = 0; k < src->n && outside; ++k) outside = a.dot(src->x[k]) + d < 0;
    if (outside) return false;
    clip(*src, *dst, a, d);
    if (dst->n == 0) return false;
    std::swap(src, dst);
  }
  const Vec3 normal_area = 0.5 * (tri[1] - tri[0]).cross(tri[2] - tri[0]);
  const double tri_area = normal_area.norm();
  if (!(tri_area > 0)) return false;
  const Vec3 n = normal_area / tri_area;
  // Fan from vertex 0: each sub-triangle's area, first and second moments (exact for linear and
  // quadratic integrands: ∫ f g dA = A/12 (Σ fᵢgᵢ + Σfᵢ Σgᵢ)).
  const Poly& r = *src;
  double area = 0;
  Vec3 first = Vec3::Zero(), second = Vec3::Zero();
  for (int i = 1; i + 1 < r.n; ++i) {
    const Vec3 &a = r.x[0], &b = r.x[i], &c = r.x[i + 1];
    const double ai = 0.5 * (b - a).cross(c - a).dot(n);
    const Vec3 sum = a + b + c;
    area += ai;
    first += ai / 3.0 * sum;
    second += ai / 12.0 *
              (a.cwiseProduct(a) + b.cwiseProduct(b) + c.cwiseProduct(c) + sum.cwiseProduct(sum));
  }
  if (!(area > 0)) return false;
  side.volume3 += first.dot(n);
  side.area += area * n;
  side.moment += first.cross(n);
  side.centroid_moment += 0.5 * second.cwiseProduct(n);
  side.surface += area;
  return true;
}

Overlap combine(const OverlapSide& a, const OverlapSide& b, const Vec3& origin) {
  Overlap o;
  o.volume = (a.volume3 + b.volume3) / 3.0;
  o.area = a.area;
  if (o.volume > 0) o.centroid = origin + (a.centroid_moment + b.centroid_moment) / o.volume;
  return o;
}

}  // namespace asperity::contact
