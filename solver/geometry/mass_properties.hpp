// Exact mass properties of a closed triangle surface (the solid it bounds, unit density), and the
// size and shape numbers derived from them.
#pragma once

#include "solver/core/mesh.hpp"
#include "solver/core/vec.hpp"

namespace asperity::geometry {

struct MassProperties {
  double volume = 0;  // m³
  Vec3 centroid;      // m
  Mat3 covariance;    // ∫ (x−c)(x−c)ᵀ dV, m⁵
  Mat3 inertia;  // ∫ (|x−c|² 1 − (x−c)(x−c)ᵀ) dV about the centroid, m⁵ (× density = kg m²)
  Vec3 principal_moments;  // eigenvalues of `inertia`, ascending, m⁵
  Mat3 principal_axes;     // unit columns matching principal_moments, right-handed
  // Semi-axes a ≥ b ≥ c of the inertia-equivalent solid ellipsoid (same second moments about the
  // centroid): a_k = √(5 λ_k / V), λ_k the covariance eigenvalues; a lies along column 0 of
  // principal_axes (the smallest moment), c along column 2. m.
  Vec3 ellipsoid_semi_axes;
  Vec3 extents;                  // bounding-box lengths L ≥ I ≥ S in the principal frame, m
  double equivalent_radius = 0;  // (3V / 4π)^{1/3}, m
  double elongation = 0;         // b / a of the inertia-equivalent ellipsoid, in (0, 1]
  double flatness = 0;           // c / b of the inertia-equivalent ellipsoid, in (0, 1]
};

// Volume, centroid and second moments as the sum over the tetrahedra (o, p0, p1, p2) that each
// face spans with a reference point o (the divergence theorem; exact for polyhedra): a simplex
// with vertices v0..v3 and volume V has ∫ x dV = V s/4 and ∫ x xᵀ dV = V/20 (Σ vₖvₖᵀ + s sᵀ),
// s = Σ vₖ (Tonon 2004, J. Math. Stat. 1(1):8–11; equivalent to Eberly 2002, "Polyhedral mass
// properties (revisited)"). o is the vertex mean, which keeps round-off relative to the
// particle's size rather than to its distance from the origin. Elongation and flatness come from
// the inertia-equivalent ellipsoid rather than the bounding box, so a single spike does not
// change them.
MassProperties mass_properties(const SurfaceMesh& mesh);

// The surface's area, m²: the sum of its triangles' (½ |(q − p) × (r − p)|).
double surface_area(const SurfaceMesh& mesh);

}  // namespace asperity::geometry
