// The mesh bodies a process has prepared: a later scene that meshes the same file with the same
// keys takes the tetrahedra an earlier one made (`asperity validate`'s hull dropped twice, a
// study's rigid and rigid-penalty cases at one resolution), and the CPU that making them cost is
// charged to whoever takes them. The identity of a mesh, MeshKey, is spelled here once.
#pragma once

#include <array>
#include <compare>
#include <string>

#include "solver/core/mesh.hpp"
#include "solver/scene/scene.hpp"

namespace asperity::run {

// What a mesh body's tetrahedra are made from: the file's bytes and the scene's meshing keys.
struct MeshKey {
  std::string bytes;  // the file's contents; empty where only the keys are compared
  int faces = 0;
  double scale = 1, element_size = 0;
  bool focused = false;
  std::array<double, 3> focus{};
  double focus_radius = 0, growth = 0, far = 0;
  bool deformable = false;
  auto operator<=>(const MeshKey&) const = default;
};

// The meshing keys of a mesh shape (its file not read: `bytes` empty). `deformable`: the body's
// tetrahedra are finite elements (run_fdem repairs only those).
MeshKey mesh_key(const scene::MeshShape& shape, bool deformable);

// The body's tetrahedra through the geometry pipeline, in the mesh file's frame, made once per
// process for one file and one key; `key` prefixes the pipeline's messages (the scene key path).
TetMesh mesh_body(const scene::MeshShape& shape, const std::string& key, bool deformable);

// The CPU seconds that the meshes this thread took from the process's prepared meshes (made for
// an earlier scene with the same file and meshing keys, instead of making them again) cost the
// thread that made them, summed over the thread's life. A caller that times a scene by its
// thread's CPU adds this one's change across the call: the scene then costs what it would alone,
// whichever scene made the mesh first (the study's cases, study_run.cpp).
double kept_mesh_cpu_seconds();

}  // namespace asperity::run
