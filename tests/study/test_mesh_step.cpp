// A time step no sliver sets (issue 11, item 5), on a sample of the full study's meshes: the
// penalty contact at a scene's default penalty pulling the predicted step at most 2× below the
// elements' own limit. Every particle and resolution of the full study against h/c (h the
// shortest surface edge, c the P-wave speed): reports/fem/mesh_step.md (mesh_step_survey).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "solver/geometry/mass_properties.hpp"
#include "solver/geometry/mesh_pipeline.hpp"
#include "solver/geometry/random_particle.hpp"
#include "solver/geometry/tet_quality.hpp"
#include "solver/geometry/tetrahedralize.hpp"
#include "study/mesh_step_survey.hpp"
#include "study/study_def.hpp"
#include "study/study_meshes.hpp"

namespace asperity::study {
namespace {

// Particles the bound was not tuned on (neither the benchmark's particle nor the default study's
// first ten), one of each kind of the set (even entries ballast-like and angular, odd rock-like,
// flat and elongated) at the coarsest, a middle and the reference resolution.
//
// What holds and is asserted: every mesh is made (a mesher failure would be this row's error),
// and at a scene's default (max_contact_factor 2 met by face-penalty, fdem::limit_face_penalty;
// at α = 10 as asked the contact pulled the step 1.1–4.3× below the elements' limit on the full
// set) the contact pulls the predicted step at most 2× below the elements' own limit. The
// penalty is not lowered further than it must be: the factor is within the search's 2 % of 2
// wherever a face was lowered at all. The element bound 1/3 ≤ dt_element·c/h ≤ 3 is the
// next test's; the other two fixes (one penalty, contact mass) are tests/fdem/test_time_step.cpp's.
TEST(MeshStep, ContactCostsAtMostTwiceTheElementStep) {
  const StudyDef def = load_study(std::string(ASPERITY_SOURCE_DIR) + "/data/study/full.json");
  for (const std::size_t particle : {16UL, 33UL, 42UL}) {
    for (const MeshStep& m : mesh_steps(def, particle, {100, 500, 2000}, false)) {
      SCOPED_TRACE(m.particle + " at " + std::to_string(m.faces) + " triangles");
      ASSERT_EQ(m.error, "");
      EXPECT_LE(m.face_factor(), 2.0 + 1e-9);
      if (m.face_scale_min < 1) {
        // The search stops within 2 % of the factor (fdem/contact_step.cpp, kMeetTolerance) on
        // these nine meshes; it may run out of its six steps first (1.92–1.96 on 4 of 161 lowered
        // meshes of the bench_fem set, reports/fem/collision_cost.md).
        EXPECT_GE(m.face_factor(), 2.0 * 0.98 - 1e-9);
      }
      // α = 10 as asked is what it was: limited only by lowering.
      EXPECT_GE(m.contact_factor(), m.face_factor() - 1e-9);
    }
  }
}

// No sliver sets the element step (issue 11, item 5): 1/3 ≤ dt_element·c/h ≤ 3, h the shortest
// surface edge and c the P-wave speed (a well-shaped linear tetrahedron with lumped mass gives
// 0.5–1). The sample: the six meshes of the full study that were lowest before the lifting
// ranked its rounds by the element step itself (0.04–0.12: caps of four surface vertices,
// reports/fem/mesh_step.md), and particles 16 and 42 (rock-like and ballast-like, not tuned on)
// at 100, 500 and 2000 triangles, and the two meshes the round-5 mesher left outside the bound:
// ballast_09 at 1000 triangles (3.03: its shortest edge a simplification leftover, 0.048 of
// its ring's mean; the short-edge collapse, geometry/remove_short_edges.hpp) and ballast_29 at
// 2000 (0.314: a tetrahedron on a face lifted onto an apex shared by 11 faces; lifting again
// with own apexes, TetOptions::min_element_step_ratio). The full set (250 meshes) is in
// reports/fem/mesh_step.md.
// Geometry invariance: the mesh's surface is the simplified surface itself (same vertices,
// bit for bit, and the same triangles: lifting adds interior points only), and the tetrahedra
// fill its volume to round-off.
TEST(MeshStep, NoSliverSetsTheElementStep) {
  const StudyDef def = load_study(std::string(ASPERITY_SOURCE_DIR) + "/data/study/full.json");
  const std::vector<std::pair<std::size_t, long>> sample{
      {36, 250}, {33, 1000}, {32, 500}, {14, 250}, {2, 1000},  {12, 250}, {16, 100},
      {16, 500}, {16, 2000}, {42, 100}, {42, 500}, {42, 2000}, {8, 1000}, {28, 2000}};
  double lowest = 1e300;
  for (const auto& [particle, faces] : sample) {
    const MeshStep m = mesh_steps(def, particle, {faces}, false).front();
    SCOPED_TRACE(m.particle + " at " + std::to_string(faces) + " triangles");
    ASSERT_EQ(m.error, "");
    EXPECT_GE(m.element_ratio(), 1.0 / 3.0);
    EXPECT_LE(m.element_ratio(), 3.0);
    lowest = std::min(lowest, m.element_ratio());
    const geometry::PreparedParticle p =
        particle_mesh(particle_source(def, particle), m.particle, faces);
    ASSERT_EQ(p.tets.surface, p.surface.faces);
    ASSERT_TRUE(p.tets.nodes.leftCols(p.surface.vertices.cols()) == p.surface.vertices);
    const double v = geometry::mass_properties(p.surface).volume;
    // Σ of signed tetrahedron volumes against the surface's divergence-theorem volume: the same
    // solid, so they agree to round-off (1e-12 relative; about 1e-15 measured).
    EXPECT_NEAR(geometry::tet_quality(p.tets).volume_sum, v, 1e-12 * v);
  }
  RecordProperty("lowest_element_ratio", std::to_string(lowest));
}

// The cost repair (issue 11, item 6; TetOptions::min_mean_edge_step_ratio): on the particles of
// the set whose 1000-face mesh at the bench_fem scene's 5 cm had an element step below 0.1 h̄/c
// (h̄ the mean surface edge), the lifting is retried under other settings and the mesh of least
// tetrahedra × element frequency whose contact step is no shorter is kept. Asserted on the
// three whose collision cost it halved (the settings were chosen on them: rock_24, ballast_13,
// rock_06; measured work tetrahedra × steps 0.51–0.54 of before, reports/fem/collision_cost.md)
// and on two it was not tuned on (rock_16, rock_46: 0.91 and 0.94): the work never rises, the
// contact step never shortens, the surface is kept; on the tuned three the element step at least
// 1.5× longer (measured 1.92–2.01×). A mesh at or above the bound (rock_02, 0.149) is the same
// mesh, bit for bit, with the repair on or off.
TEST(MeshStep, CostRepairShortensTheSlowMeshesAndLeavesTheRest) {
  // The particles as the full study reads them from the set, at the bench_fem scene's 5 cm and
  // without the study's centring and orientation: the bench's meshes.
  const StudyDef def = load_study(std::string(ASPERITY_SOURCE_DIR) + "/data/study/full.json");
  const auto mesh = [&](const std::string& name, double ratio) {
    for (const ParticleSource& p : def.particles) {
      if (p.name != name) continue;
      geometry::ParticleDef pd = p.generated;
      pd.size = 0.05;
      geometry::PipelineOptions o;
      o.faces = 1000;
      o.tet.min_mean_edge_step_ratio = ratio;
      return geometry::prepare_particle(geometry::random_particle(pd), name, o);
    }
    throw std::runtime_error("no particle " + name);
  };
  for (const char* name : {"rock_24", "ballast_13", "rock_06", "rock_16", "rock_46"}) {
    SCOPED_TRACE(name);
    const geometry::PreparedParticle off = mesh(name, 0), on = mesh(name, 0.1);
    const geometry::StepScales a = geometry::step_scales(off.tets),
                               b = geometry::step_scales(on.tets);
    ASSERT_LT(geometry::mean_edge_step_ratio(off.surface, a.element_frequency), 0.1);
    const double work_a = static_cast<double>(off.tets.tets.cols()) * a.element_frequency;
    const double work_b = static_cast<double>(on.tets.tets.cols()) * b.element_frequency;
    EXPECT_LE(work_b, work_a);
    EXPECT_LE(b.contact_frequency2, a.contact_frequency2);
    EXPECT_TRUE(on.tets.surface == off.tets.surface);
    const double v = geometry::mass_properties(on.surface).volume;
    EXPECT_NEAR(geometry::tet_quality(on.tets).volume_sum, v, 1e-12 * v);
    if (std::string(name) == "rock_24" || std::string(name) == "ballast_13" ||
        std::string(name) == "rock_06") {
      EXPECT_LE(b.element_frequency, a.element_frequency / 1.5);
    }
  }
  const geometry::PreparedParticle off = mesh("rock_02", 0), on = mesh("rock_02", 0.1);
  EXPECT_GE(geometry::mean_edge_step_ratio(off.surface,
                                           geometry::step_scales(off.tets).element_frequency),
            0.1);
  EXPECT_TRUE(on.tets.nodes == off.tets.nodes);
  EXPECT_TRUE(on.tets.tets == off.tets.tets);
}

}  // namespace
}  // namespace asperity::study
