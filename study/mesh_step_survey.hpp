// The time step of every mesh the study makes against the one its surface resolution implies
// (issue 11, item 5): is the predicted critical step set by the element size, or by the worst
// element or the penalty layer? Used by tests/study/test_mesh_step.cpp (a sample) and by
// `mesh_step_survey` (every particle and resolution; reports/fem/mesh_step.md).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "study/study_def.hpp"

namespace asperity::study {

// One mesh: particle `particle` of the study at `faces` surface triangles (study_meshes.hpp),
// deformable, a gap above the block, its predicted critical step (fdem/time_step.hpp) under the
// solver's default penalty α and under the study's own.
//   h: the shortest edge of the surface triangles, m;
//   c: the P-wave speed √((λ + 2μ)/ρ) of the particle's material, m/s.
// h/c is the step a mesh of that surface resolution calls for; the ratios below are the
// predicted steps over it (1/3 ≤ dt_element·c/h ≤ 3: no sliver sets the step, the item's bound).
struct MeshStep {
  std::string particle;
  long faces = 0;
  long tets = 0;
  double h = 0, c = 0;
  double dt_element = 0;   // s, elements alone (no contact)
  double dt_contact = 0;   // s, penalty contact alone, default α = 10
  double dt_critical = 0;  // s, both together (the step a run scales), α = 10
  std::string limited_by;  // "element" or "contact", α = 10
  // α = 10 lowered until the contact costs at most a factor 2 (fdem::limit_penalty): the step
  // and the α it leaves.
  double dt_limited = 0, alpha_limited = 0;
  // The same factor met by face-penalty (a scene's default) and by contact mass scaling: the
  // step, the least penalty factor of any contact tetrahedron, the mass added / the body's.
  double dt_face = 0, face_scale_min = 1, dt_mass = 0, mass_added = 0;
  double dt_critical_study = 0;  // s, both together at the study's α (= 10 when unset)
  double seconds = 0;            // CPU of meshing (TetGen's children in) and the step prediction
  std::string error;             // non-empty: the mesher (or the world) failed; nothing above
  double element_ratio() const { return dt_element * c / h; }
  double critical_ratio() const { return dt_critical * c / h; }
  double limited_ratio() const { return dt_limited * c / h; }
  // How far the contact pulls the step below the elements' own (≤ 2: the item's bound), at
  // α = 10 and at the scene default.
  double contact_factor() const { return dt_element / dt_critical; }
  double limited_factor() const { return dt_element / dt_limited; }
  double face_factor() const { return dt_element / dt_face; }
  double mass_factor() const { return dt_element / dt_mass; }
  double face_ratio() const { return dt_face * c / h; }
};

// Meshes particle `index` of `def` at each of `faces` and predicts each mesh's step: elements,
// α = 10, and the factor 2 met by face-penalty; with `all_fixes` also by one penalty and by
// contact mass, and at the study's α. A mesher failure on one resolution is that row's `error`;
// the rest go on.
std::vector<MeshStep> mesh_steps(const StudyDef& def, std::size_t index,
                                 const std::vector<long>& faces, bool all_fixes = true);

}  // namespace asperity::study
