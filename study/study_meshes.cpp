// The study's particles and meshes (study/study_meshes.hpp).
#include "study/study_meshes.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>

#include "solver/core/error.hpp"
#include "solver/fdem/structured_mesh.hpp"
#include "solver/geometry/local_curvature.hpp"
#include "solver/geometry/mass_properties.hpp"
#include "solver/geometry/random_particle.hpp"
#include "solver/geometry/read_mesh.hpp"
#include "solver/geometry/splitmix64.hpp"

namespace asperity::study {

namespace {

// Uniform random rotation (Shoemake 1992, "Uniform random rotations", Graphics Gems III): a unit
// quaternion from three uniforms.
Mat3 random_rotation(std::uint64_t seed) {
  geometry::SplitMix64 rng{seed};
  const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1), tau = 2 * std::numbers::pi;
  const Quat q(b * std::cos(tau * u3), a * std::sin(tau * u2), a * std::cos(tau * u2),
               b * std::sin(tau * u3));
  return q.normalized().toRotationMatrix();
}

Mat3 orientation_matrix(const StudyDef& def, std::size_t index) {
  const ParticleSource& p = def.particles.at(index);
  // The k-th of K orientations: seeded by the particle's place in the list given and k, so a
  // particle's first orientations stay the same when K grows.
  if (p.orientation >= 0) {
    return random_rotation(0x0e1e47ULL + 7919ULL * p.source_index +
                           104729ULL * static_cast<std::uint64_t>(p.orientation));
  }
  // Seeded by the particle's place in the study.
  if (def.random_orientation) return random_rotation(0x5eedULL + 7919ULL * index);
  const Vec3 r = def.orientation_deg * (std::numbers::pi / 180);
  return (Eigen::AngleAxisd(r.z(), Vec3::UnitZ()) * Eigen::AngleAxisd(r.y(), Vec3::UnitY()) *
          Eigen::AngleAxisd(r.x(), Vec3::UnitX()))
      .toRotationMatrix();
}

}  // namespace

SurfaceMesh particle_source(const StudyDef& def, std::size_t index) {
  const ParticleSource& p = def.particles.at(index);
  SurfaceMesh m;
  if (p.file.empty()) {
    const geometry::ParticleDef& d = p.generated;
    if (const std::string problem = geometry::particle_def_problem(d); !problem.empty()) {
      throw InputError(def.file.string() + ": particles: \"" + p.name + "\": " + problem);
    }
    m = geometry::random_particle(d);
  } else {
    geometry::PipelineOptions o;
    o.read.scale = p.scale;
    o.tetrahedralize = false;
    m = geometry::prepare_particle(p.file, o).surface;
  }
  const geometry::MassProperties props = geometry::mass_properties(m);
  const double s = def.particle_size ? *def.particle_size / (2 * props.equivalent_radius) : 1.0;
  const Mat3 rot = orientation_matrix(def, index);
  for (Eigen::Index i = 0; i < m.vertices.cols(); ++i) {
    m.vertices.col(i) = rot * (s * (m.vertices.col(i) - props.centroid));
  }
  return m;
}

geometry::PreparedParticle particle_mesh(const SurfaceMesh& source, const std::string& name,
                                         long faces) {
  geometry::PipelineOptions o;
  o.faces = faces;
  o.tetrahedralize = true;
  return geometry::prepare_particle(source, name, o);
}

fdem::WorldDef particle_on_block(const TetMesh& tets, const StudyDef& def, fdem::BodyKind kind,
                                 double radius) {
  fdem::WorldDef w;
  TetMesh m = tets;
  m.nodes.row(2).array() += def.gap - m.nodes.row(2).minCoeff();
  w.bodies.push_back({.name = "particle",
                      .kind = kind,
                      .mesh = m,
                      .material = def.material,
                      .velocity = Vec3(0, 0, -def.speed)});
  const double half = 2 * radius + 0.01;
  w.bodies.push_back(
      {.name = "block",
       .kind = fdem::BodyKind::fixed,
       .mesh = fdem::box_mesh(Vec3(-half, -half, -half), Vec3(half, half, 0), 1, 1, 1),
       .material = def.block_material});
  if (def.penalty_alpha) w.contact.alpha = *def.penalty_alpha;
  return w;
}

SurfaceMesh read_surface(const std::filesystem::path& file) {
  const geometry::PolygonSoup soup = geometry::read_mesh_file(file);
  SurfaceMesh s;
  s.vertices = soup.points;
  s.faces.resize(3, static_cast<Eigen::Index>(soup.polygons.size()));
  for (std::size_t f = 0; f < soup.polygons.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      s.faces(k, static_cast<Eigen::Index>(f)) =
          static_cast<int>(soup.polygons[f][static_cast<std::size_t>(k)]);
    }
  }
  return s;
}

LocalRadii local_radii(const std::filesystem::path& file) {
  const SurfaceMesh s = read_surface(file);
  const geometry::LocalCurvature c =
      geometry::lowest_point_curvature(s, 2.5 * geometry::mean_edge_length(s));
  return {c.radius_min, c.radius_max, c.equivalent_radius()};
}

}  // namespace asperity::study
