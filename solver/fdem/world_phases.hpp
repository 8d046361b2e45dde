// The FEM/DEM world's phases that its files share (fdem_world.hpp is the interface): building
// (build_world.cpp), the two contact methods (potential_contact.cpp, volume_contact.cpp), the
// step (fdem_world.cpp) and its prediction (time_step.cpp, contact_step.cpp). Not for use outside
// solver/fdem/.
#pragma once

#include <vector>

#include "solver/contact/munjiza_potential.hpp"
#include "solver/fdem/fdem_world.hpp"

namespace asperity::fdem::detail {

// Surface tetrahedron `tet`'s four nodes, as they are now.
inline contact::TetNodes gather(const World& w, int tet) {
  return {w.x.col(w.surface_tets(0, tet)), w.x.col(w.surface_tets(1, tet)),
          w.x.col(w.surface_tets(2, tet)), w.x.col(w.surface_tets(3, tet))};
}

// Broad phase: the candidate pairs anew, the friction history carried across (fdem_world.cpp).
void rebuild_pairs(World& w);

// Contact forces of every candidate pair into w.f under Munjiza's potential, with Coulomb
// friction, energy and the per-body output (potential_contact.cpp).
void potential_contact_forces(World& w, double dt);

// The volume laws' forces and torques on the rigid bodies, with friction (volume_contact.cpp).
void volume_contact_forces(World& w, double dt);

// Contact forces, then internal forces, each timed (fdem_world.cpp).
void compute_forces(World& w, double dt);

// Rigid bodies: total force and torque about the centre from their nodes' forces (fdem_world.cpp).
void reduce_rigid(World& w);

// The penalty spring of every surface face of deformable body `body`, as extra stiffness of the
// element that owns the face, each scaled by face_scale[face] when given (time_step.cpp; the
// predicted step and the contact step's remedies use it).
std::vector<fem::ElementExtraStiffness> face_springs(
    const World& w, int body, const std::vector<double>* face_scale = nullptr);

}  // namespace asperity::fdem::detail
