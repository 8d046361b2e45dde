// The whole geometry pipeline for one particle: read and repair (or take a generated surface),
// simplify to exactly N triangles, tetrahedralize keeping them, and measure what changed. Used
// by `asperity mesh`, by mesh bodies in scenes and by the particle-geometry study.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "solver/core/mesh.hpp"
#include "solver/geometry/mass_properties.hpp"
#include "solver/geometry/read_mesh.hpp"
#include "solver/geometry/repair_mesh.hpp"
#include "solver/geometry/shape_metrics.hpp"
#include "solver/geometry/tet_quality.hpp"
#include "solver/geometry/tetrahedralize.hpp"

namespace asperity::geometry {

struct PipelineOptions {
  long faces = 0;              // exact triangle count wanted; 0 keeps the input's
  ReadOptions read;            // scale
  bool tetrahedralize = true;  // false: surface only (rigid bodies need no tetrahedra)
  TetOptions tet;
  // How a bad tet.element_size is named in the InputError: the scene file and key, or the
  // command and option; empty: "SOURCE: element_size".
  std::string element_size_key;
};

struct PreparedParticle {
  std::string source_name;  // file or generator description
  SurfaceMesh source;       // after repair
  MassProperties source_props;
  MeshLog log;          // repairs and warnings
  SurfaceMesh surface;  // exactly `faces` triangles, closed, manifold, outward
  MassProperties props;
  MeshCheck check;     // of `surface`, with self-intersections
  ShapeChange change;  // `surface` against `source`
  TetMesh tets;        // empty when not asked for; its surface is `surface` bisected to
                       // element_size when that is set
  ElementSize element_size;
  TetQuality quality;
  double seconds_read = 0, seconds_simplify = 0, seconds_tetrahedralize = 0;  // wall-clock
};

// From a file (read_mesh_file → repair_mesh → ...). InputError for bad input or an impossible
// face count; std::runtime_error when a step fails on valid input.
PreparedParticle prepare_particle(const std::filesystem::path& file,
                                  const PipelineOptions& options);
// From a surface already in memory (e.g. random_particle), checked and repaired the same way.
PreparedParticle prepare_particle(const SurfaceMesh& source, const std::string& name,
                                  const PipelineOptions& options);

// mesh.json (docs/contract.md "Outputs", docs/geometry.md): every number above, SI units.
nlohmann::json mesh_report(const PreparedParticle& p);

// DIR/surface.off, DIR/tets.vtk (when tetrahedralized), DIR/mesh.json last; each atomically.
void write_prepared_particle(const PreparedParticle& p, const std::filesystem::path& dir);

}  // namespace asperity::geometry
