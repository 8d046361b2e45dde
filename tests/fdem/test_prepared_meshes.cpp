// The meshes a process keeps (run/prepared_meshes.hpp, PreparedMeshes): a scene that takes a mesh
// an earlier scene made is charged what making it cost (kept_mesh_cpu_seconds), so that a study
// case costs the same whichever case of its mesh ran first.
#include <gtest/gtest.h>

#include "scenes/particle_block_impact.hpp"
#include "solver/core/clock.hpp"
#include "solver/run/prepared_meshes.hpp"
#include "solver/run/run_fdem.hpp"

namespace asperity::run {
namespace {

// The first rigid scene makes the mesh (nothing charged); a second rigid scene of the same file
// and keys takes it and is charged more than nothing and no more than the first scene's whole
// CPU, TetGen's children included on both sides (its making is a part of that); a fem scene of the
// same file makes its own (a deformable body's mesh is another key: the mesher's step repair),
// nothing charged.
TEST(PreparedMeshes, ATakenMeshIsChargedWhatMakingItCost) {
  const double k0 = kept_mesh_cpu_seconds();
  const double c0 = thread_and_children_cpu_seconds();
  impact("mesh-first", "rigid", 1.0, 0, false, 2e-5);
  const double first_cpu = thread_and_children_cpu_seconds() - c0;
  const double k1 = kept_mesh_cpu_seconds();
  EXPECT_EQ(k1, k0);
  impact("mesh-second", "rigid", 2.0, 0, false, 2e-5);
  const double k2 = kept_mesh_cpu_seconds();
  EXPECT_GT(k2 - k1, 0.0);
  EXPECT_LE(k2 - k1, first_cpu);
  impact("mesh-deformable", "fem", 1.0, 0, false, 2e-5);
  EXPECT_EQ(kept_mesh_cpu_seconds(), k2);
}

}  // namespace
}  // namespace asperity::run
