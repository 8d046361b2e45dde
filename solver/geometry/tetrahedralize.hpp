// Tetrahedralizing the solid a closed triangle surface bounds, keeping those triangles exactly.
#pragma once

#include <vector>

#include "solver/core/mesh.hpp"
#include "solver/geometry/element_size.hpp"

namespace asperity::geometry {

struct TetOptions {
  // TetGen's quality bound "q": largest circumradius-to-shortest-edge ratio of a tetrahedron,
  // met by inserting points inside the solid only (never on the surface, switch Y). 0 turns
  // quality refinement off (a constrained Delaunay tetrahedralization of the surface points
  // only). 2 is TetGen's own default bound; tighter bounds add many interior points near
  // poorly shaped surface triangles.
  double radius_edge_ratio = 2.0;
  // Also asked of TetGen with q (its "q ratio/angle" form): smallest dihedral angle, degrees.
  // 0 leaves TetGen's default. Interior refinement cannot fix a sliver touching the surface.
  double min_dihedral_deg = 0;
  // Lifting flat surface tetrahedra (docs/geometry.md, "Surface tetrahedra"). On nearly flat
  // patches the constrained Delaunay tetrahedralization keeps "caps", tetrahedra of four surface
  // vertices whose height above a boundary face is a few % of their longest edge; no interior
  // point can remove them, since the fourth vertex lies inside every sphere through the face
  // that bulges inward. A face whose tetrahedron is lower than this fraction of that
  // tetrahedron's longest edge is therefore given an imposed tetrahedron instead: an interior
  // apex below it (shared with a lifted neighbour where that is as good), the three triangles
  // from the face's edges to the apex added as internal facets, and TetGen run again; up to
  // max_lift_rounds rounds. The result is the round's mesh with the largest predicted step
  // (step_scales) and never a worse one than without lifts. 0 turns lifting off. 0.3 is where
  // the face's penalty stiffness p·A·4/h is at most 0.82/0.3 ≈ 2.7× that of a regular
  // tetrahedron's face (height/edge √(2/3)); higher bounds add tetrahedra for little gain.
  double min_surface_height_ratio = 0.3;
  int max_lift_rounds = 8;
  double lift_depth = 0.5;    // apex depth below the face centroid, × the face's longest edge
  double lift_spacing = 0.3;  // least distance between two apexes, × the face's longest edge
  // Least volume / longest edge³ of the tetrahedron between two lifted neighbours' walls (a
  // regular tetrahedron has 1/(6√2) ≈ 0.118).
  double min_wedge_volume_ratio = 0.02;
  // An apex whose tetrahedra include one with least height below this fraction of its longest
  // edge is taken out again.
  double min_apex_tet_height_ratio = 0.03;
  // Lifting again with an apex of its own for every lifted face (no apex shared with a
  // neighbour) when the mesh's element step is below this fraction of h/c (h the shortest
  // surface edge, c the P-wave speed; issue 11, item 5 asks 1/3 ≤ dt_element·c/h ≤ 3 of every
  // mesh the study makes): the result is the one with the longer element step. A shared apex
  // leaves the fewest tetrahedra but can stand far across a face (docs/geometry.md, "Surface
  // tetrahedra"). Meshes at or above the bound, and meshes with an element_size (whose step is
  // the size's), are returned as before, bit for bit. Measured at ν = 0.25
  // (element_step_ratio); 0 turns it off.
  double min_element_step_ratio = 1.0 / 3.0;
  // The cost repair (issue 11, item 6: the collision's cost growing no faster than N^1.4): the
  // lifting is greedy, and where it ends on a given surface moves with its settings (rock_24 of
  // the particle set at 1000 faces: element steps 80–155 ns over six equally defensible
  // settings, for 1 953–2 177 tetrahedra). When the mesh's element step is below this fraction
  // of h̄/c (h̄ the mean surface edge, c the P-wave speed; mean_edge_step_ratio), the rounds run
  // again under a fixed list of other settings (tetrahedralize.cpp), and the mesh with the
  // least work per simulated second, tetrahedra × element frequency, whose contact step is not
  // shorter, is kept. 0.1
  // is about 0.6 of the median over the particle set at 1000 faces (0.161; 0.241 at 100): it
  // catches the meshes whose step a flat cap or a light surface node sets, and leaves the rest
  // as before, bit for bit. Meshes with an element_size are left alone, as above; 0 turns it
  // off.
  double min_mean_edge_step_ratio = 0.1;
  // Element size apart from the surface (issue 11; docs/geometry.md, "Element size"): when set,
  // the surface triangles are first bisected in their own planes down to the size
  // (subdivide_surface), and TetGen refines the interior until each tetrahedron's circumradius
  // is within the size at its vertices (switch m). Unset: the surface triangles are the
  // elements' faces, as before.
  ElementSize element_size;
  // Budgets (issue 18): TetGen's interior points (switch S; an unattainable quality bound such as
  // 0.5 otherwise inserts points without end) and wall-clock seconds per TetGen run (in a child
  // process, killed at the budget). Passing either is an InputError naming the bound. < 0: the
  // Steiner budget is 20 × the surface vertices + 4 × the estimated tetrahedra of the element
  // size, at least 100 000.
  long max_steiner_points = -1;
  double time_budget_s = 300;
};

// The Steiner budget TetOptions::max_steiner_points < 0 stands for, for this surface.
long default_steiner_budget(const SurfaceMesh& surface, const ElementSize& size);

// Height of the tetrahedron on each surface face above that face, 3V/A, and its longest edge:
// Munjiza's potential rises from the face over a quarter of that height, so the face's penalty
// stiffness grows as 1/height (fdem/build_world.cpp) and the contact step shrinks as √height.
struct SurfaceTetHeight {
  int tet = -1;
  double height = 0;        // m
  double longest_edge = 0;  // m
};
// One entry per `mesh.surface` column, in that order.
std::vector<SurfaceTetHeight> surface_tet_heights(const TetMesh& mesh);

// What the explicit step of the mesh scales with, material aside. Element: the largest element
// eigenvalue of a linear tetrahedron grows as (wave speed / least height)², so the step is
// proportional to the least height 3V/A_max over the tetrahedra. Contact: the Gershgorin bound
// of time_step.hpp, Σ_faces p A (1/h) / 3 over the node's lumped mass, is proportional to
// Σ_faces A/H over Σ_tets V at the node (H = 3V/A of the face's tetrahedron).
//
// The least height is a proxy only: the element step is the mass-split bound of the assembled
// mesh (fem::element_critical_step), in which a flat tetrahedron between large neighbours holds
// their mass. element_frequency is that bound for a unit material (E = 1 Pa, ν = 0.25,
// ρ = 1 kg/m³), so dt_element ∝ 1/element_frequency for every material of that ν. Lifting ranks
// its rounds by it: on ballast_37 of the study at 250 faces the first round lowered the least
// height to 0.96× but raised the element step 6.6× (the flat tetrahedron it left lies between
// long-edged ones), and the least height alone threw that round away.
struct StepScales {
  double least_height = 0;        // m; a flat tetrahedron's share of dt_element
  double element_frequency = 0;   // 1/m (unit material); dt_element ∝ 1/element_frequency
  double contact_frequency2 = 0;  // 1/m²; dt_contact ∝ 1/√contact_frequency2
};
StepScales step_scales(const TetMesh& mesh);

// dt_element·c/h of a mesh with unit-material element frequency `element_frequency`
// (StepScales) on `surface` (h its shortest edge), undamped, at ν = 0.25: the ratio issue 11,
// item 5 bounds by 1/3 and 3 (its ν dependence is that of the element bound over c, weak).
double element_step_ratio(const SurfaceMesh& surface, double element_frequency);

// dt_element·c/h̄, as element_step_ratio but against the mean surface edge h̄ (over the faces'
// edges): the step against the size of the typical element, which is what the cost follows.
double mean_edge_step_ratio(const SurfaceMesh& surface, double element_frequency);

// Constrained Delaunay tetrahedralization with TetGen 1.5 (Si 2015, ACM TOMS 41(2):11), switches
// "pYzQ" (+ "q" when asked, "m" with an element size, "S" budget; geometry/tetgen_call.hpp): p
// reads the surface as a piecewise linear complex, Y forbids Steiner points on it, so the
// boundary of the result is exactly the (subdivided) input triangles. The result's nodes begin
// with the surface vertices in their order (checked; with an element size, the input's vertices
// then the bisection midpoints), then the lift apexes (TetOptions), then TetGen's interior
// points; its tetrahedra have positive orientation ((b−a)×(c−a))·(d−a) > 0, and `surface` is the
// (subdivided) surface's face array. Throws InputError when a budget is passed,
// std::runtime_error when TetGen fails (its reason in words) or when the boundary of the result
// differs from the input triangles.
TetMesh tetrahedralize(const SurfaceMesh& surface, const TetOptions& options = {});

}  // namespace asperity::geometry
