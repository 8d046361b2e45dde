// What simplification did to a particle's shape: the numbers the particle-geometry study reports.
#pragma once

#include "solver/core/mesh.hpp"
#include "solver/geometry/mass_properties.hpp"

namespace asperity::geometry {

// Asperity height of a surface point x (m): how far x stands outside the particle's
// inertia-equivalent ellipsoid E (mass_properties.hpp: centred at the centroid c, semi-axes
// a ≥ b ≥ c along the principal axes, the same second moments as the solid), measured along the
// ray from the centroid:
//     h(x) = |q| − r_E(q/|q|),  q = Rᵀ(x − c),  r_E(u) = (Σₖ uₖ² / aₖ²)^{−1/2},
// with R the principal axes. A point inside E has h < 0. The ellipsoid is the smooth reference
// shape (the degree-2 part of the particle), so h measures what sticks out of the particle's
// overall form: corners and asperities. The particle's highest asperity is the maximum of h over
// its vertices (the tips of a triangle mesh are vertices).
double max_asperity_height(const SurfaceMesh& mesh, const MassProperties& props);

// max_asperity_height / equivalent_radius: dimensionless, the same for a particle at any size.
double max_asperity_rel(const SurfaceMesh& mesh, const MassProperties& props);

// A result mesh compared with its source (each with its own mass properties).
struct ShapeChange {
  double volume_change_rel = 0;        // (V − V₀) / V₀
  double centroid_shift_rel = 0;       // |c − c₀| / r_eq,₀
  double max_asperity_rel_source = 0;  // max_asperity_rel of the source
  double max_asperity_rel = 0;         // max_asperity_rel of the result
  double max_asperity_change_rel = 0;  // max_asperity_rel − max_asperity_rel_source
  double elongation_change = 0;        // elongation − elongation₀
  double flatness_change = 0;          // flatness − flatness₀
};

ShapeChange shape_change(const SurfaceMesh& source, const MassProperties& source_props,
                         const SurfaceMesh& result, const MassProperties& result_props);

}  // namespace asperity::geometry
