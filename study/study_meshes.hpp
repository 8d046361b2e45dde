// The study's particles and meshes as the runner makes them (issue 7), for everything else that
// must see the same meshes: the source surface of a particle, its mesh at N surface triangles,
// and the world of a case at its start (particle a gap above the block).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include "solver/core/mesh.hpp"
#include "solver/fdem/fdem_world.hpp"
#include "solver/geometry/mesh_pipeline.hpp"
#include "solver/geometry/random_particle.hpp"
#include "study/study_def.hpp"

namespace asperity::study {

// Particle `index` of def.particles: its surface (generated, or read and repaired), centroid at
// the origin, scaled to def.particle_size when given, rotated to the study's orientation.
// InputError for a particle that cannot be made.
SurfaceMesh particle_source(const StudyDef& def, std::size_t index);

// That surface simplified to exactly `faces` triangles and tetrahedralized with the study's
// options (the mesher's defaults: element size = surface). As geometry::prepare_particle throws.
geometry::PreparedParticle particle_mesh(const SurfaceMesh& source, const std::string& name,
                                         long faces);

// The FEM/DEM world of a case at its start: the tetrahedral mesh (kind fem or rigid), its lowest
// point def.gap above a fixed block wider than the particle (`radius`: its equivalent-sphere
// radius, m), moving down at def.speed, penalty α the study's (the solver's default when unset).
fdem::WorldDef particle_on_block(const TetMesh& tets, const StudyDef& def, fdem::BodyKind kind,
                                 double radius);

// The triangle surface in FILE (a study mesh's surface.off), as geometry::read_mesh_file reads it.
SurfaceMesh read_surface(const std::filesystem::path& file);

// The principal radii (m, r1 ≤ r2) of the surface in FILE (a study mesh's surface.off) at its
// lowest vertex and Hertz's equivalent radius √(r1 r2) there (0: flat or concave), fitted over a
// patch of 2.5 mean edges (about two rings of vertices: the fewest that hold the quadric's six
// unknowns with room to spare; geometry/local_curvature.hpp) — the "sphere-local" model.
struct LocalRadii {
  double r1 = 0, r2 = 0, equivalent = 0;
};
LocalRadii local_radii(const std::filesystem::path& file);

}  // namespace asperity::study
