// Generated rock-like particles (issue 3, item 7); the construction and why it is valid are in
// the header.
#include "solver/geometry/random_particle.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <sstream>
#include <vector>

#include "solver/core/error.hpp"
#include "solver/geometry/geodesic_sphere.hpp"
#include "solver/geometry/mass_properties.hpp"
#include "solver/geometry/splitmix64.hpp"

namespace asperity::geometry {
namespace {

// Sum of random plane waves on the unit sphere, Σ A sin(k d·u + φ).
struct Waves {
  std::vector<Vec3> direction;
  std::vector<double> wavenumber, amplitude, phase;

  void add(SplitMix64& rng, double k, double a) {
    direction.push_back(rng.unit_vector());
    wavenumber.push_back(k);
    amplitude.push_back(a);
    phase.push_back(rng.uniform(0.0, 2.0 * std::numbers::pi));
  }
  double operator()(const Vec3& u) const {
    double s = 0;
    for (std::size_t i = 0; i < direction.size(); ++i)
      s += amplitude[i] * std::sin(wavenumber[i] * direction[i].dot(u) + phase[i]);
    return s;
  }
};

}  // namespace

long particle_face_count(long faces) {
  const long n =
      std::max(1L, std::lround(std::sqrt(static_cast<double>(std::max(faces, 1L)) / 20.0)));
  return 20 * n * n;
}

std::string particle_def_problem(const ParticleDef& d) {
  std::ostringstream s;
  // The usable ranges: a size whose cube (the volume) and whose square over the smallest
  // triangle stay far inside a double, in the units a rock is measured in (1 µm to 1 km); axis
  // ratios down to 1:20, below which a cut or the roughness folds the thin body through itself.
  if (!(d.size >= kParticleSizeMin && d.size <= kParticleSizeMax))
    s << "size must lie in [" << kParticleSizeMin << ", " << kParticleSizeMax << "] m (got "
      << d.size << ")";
  else if (!(d.elongation >= kParticleAxisRatioMin && d.elongation <= 1))
    s << "elongation must lie in [" << kParticleAxisRatioMin << ", 1] (got " << d.elongation << ")";
  else if (!(d.flatness >= kParticleAxisRatioMin && d.flatness <= 1))
    s << "flatness must lie in [" << kParticleAxisRatioMin << ", 1] (got " << d.flatness << ")";
  else if (!(d.angularity >= 0 && d.angularity <= 1))
    s << "angularity must lie in [0, 1] (got " << d.angularity << ")";
  else if (!(d.roughness >= 0 && d.roughness <= 1))
    s << "roughness must lie in [0, 1] (got " << d.roughness << ")";
  else if (d.faces < 20 || d.faces > 2'000'000)
    s << "faces must lie in [20, 2000000] (got " << d.faces << ")";
  return s.str();
}

SurfaceMesh random_particle(const ParticleDef& def) {
  if (const std::string problem = particle_def_problem(def); !problem.empty())
    throw InputError(problem);
  SplitMix64 rng{def.seed};

  Waves form;  // 1. low-order irregularity of the overall form
  for (int k = 0; k < 6; ++k) form.add(rng, rng.uniform(1.0, 3.0), 0.08 / 3.0);
  const Vec3 axes(1.0, def.elongation, def.elongation * def.flatness);

  const int cuts =
      def.angularity > 0 ? static_cast<int>(std::lround(4.0 + 16.0 * def.angularity)) : 0;
  std::vector<Vec3> normal(cuts);
  std::vector<double> depth(cuts);
  for (int k = 0; k < cuts; ++k) {
    normal[k] = rng.unit_vector();
    depth[k] = 0.3 * def.angularity * rng.uniform(0.3, 1.0);
  }

  Waves rough;  // 3. multi-scale roughness
  for (int j = 0; j < 5; ++j)
    for (int w = 0; w < 4; ++w)
      rough.add(rng, 4.0 * std::pow(2.0, j), 0.04 * def.roughness * std::pow(2.0, -0.8 * j) / 2.0);

  const int n = static_cast<int>(
      std::lround(std::sqrt(static_cast<double>(particle_face_count(def.faces)) / 20.0)));
  const SurfaceMesh sphere = geodesic_sphere(n);
  std::vector<Vec3> u(static_cast<std::size_t>(sphere.vertices.cols()));
  for (std::size_t i = 0; i < u.size(); ++i)
    u[i] = sphere.vertices.col(static_cast<Eigen::Index>(i));

  std::vector<Vec3> x(u.size());
  for (std::size_t i = 0; i < u.size(); ++i) x[i] = axes.cwiseProduct(u[i]) * (1.0 + form(u[i]));
  for (int k = 0; k < cuts; ++k) {  // 2. planar cuts, each against the body cut so far
    double support = 0;
    for (const Vec3& p : x) support = std::max(support, normal[k].dot(p));
    const double d = (1.0 - depth[k]) * support;
    for (Vec3& p : x) {
      const double h = normal[k].dot(p);
      if (h > d) p *= d / h;
    }
  }
  for (std::size_t i = 0; i < u.size(); ++i) x[i] *= 1.0 + rough(u[i]);

  SurfaceMesh mesh;
  mesh.vertices.resize(3, static_cast<Eigen::Index>(x.size()));
  for (std::size_t i = 0; i < x.size(); ++i) mesh.vertices.col(static_cast<Eigen::Index>(i)) = x[i];
  mesh.faces = sphere.faces;

  const MassProperties m = mass_properties(mesh);  // 4. centroid at the origin, exact size
  const double scale = def.size / (2.0 * m.equivalent_radius);
  mesh.vertices = scale * (mesh.vertices.colwise() - m.centroid);
  return mesh;
}

}  // namespace asperity::geometry
