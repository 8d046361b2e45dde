// Reproducible rock- and ballast-like closed surfaces standing in for scans (issue 3, item 7).
#pragma once

#include <cstdint>
#include <string>

#include "solver/core/mesh.hpp"

namespace asperity::io {
class JsonReader;
}

namespace asperity::geometry {

struct ParticleDef {
  std::uint64_t seed = 1;
  double size = 0.05;        // equivalent-sphere diameter of the result, m (exact)
  double elongation = 0.75;  // b/a of the base ellipsoid, (0, 1]
  double flatness = 0.75;    // c/b of the base ellipsoid, (0, 1]
  double angularity = 0.5;   // [0, 1]: 0 smooth; 1 many deep planar cuts (facets, sharp edges)
  double roughness = 0.3;    // [0, 1]: amplitude of the multi-scale surface noise
  long faces = 20480;        // asked-for triangle count; the result has 20 n² (see below)
};

// Triangles random_particle makes for `faces`: 20 n², n = max(1, round(√(faces/20))), the
// geodesic icosphere of frequency n (e.g. 20480 for n = 32, 60500 for n = 55).
long particle_face_count(long faces);

// The usable ranges of size (m) and of the axis ratios elongation and flatness.
inline constexpr double kParticleSizeMin = 1e-6, kParticleSizeMax = 1e3;
inline constexpr double kParticleAxisRatioMin = 0.05;

// Checks the ranges above; returns "" or the problem, which starts with the key
// ("elongation must lie in [0.05, 1] (got 2)").
std::string particle_def_problem(const ParticleDef& def);

// A generated particle's fields in JSON, as a particle set lists them (data/particles/set.json,
// `asperity particle --set`, a study's "particles": {"set": ...}): "seed" (required, ≥ 0),
// "size", "elongation", "flatness", "angularity", "roughness" and "faces" (in [20, 2,000,000]),
// each ParticleDef's default when absent. The one reader of those fields; their ranges are
// particle_def_problem's, for the caller to check where it reports them.
ParticleDef read_particle_def(const io::JsonReader& r);

// A star-shaped particle r(u)·u over the unit sphere, built on a geodesic icosphere (each
// icosahedron face split into n² triangles, vertices projected onto the sphere):
//  1. base form: the ellipsoid with semi-axes (1, elongation, elongation·flatness) times
//     1 + a few random low-order plane waves on the sphere (wave numbers 1–3, ±8 % in radius),
//     so no two particles share the same overall form;
//  2. angularity: K = round(4 + 16·angularity) random planes cut the body, each at a depth of
//     up to 30 %·angularity of the body's support in its direction (zero cuts at angularity 0).
//     A vertex outside a plane moves along its ray onto the plane, which keeps the body
//     star-shaped and gives flat facets with sharp edges;
//  3. roughness: 5 octaves of random plane waves, wave numbers 4·2ʲ with amplitude
//     0.04·roughness·2^(−0.8 j) (a fractal-like spectrum), multiplying the radius;
//  4. translated so that the centroid is at the origin and scaled to the equivalent diameter
//     `size`.
// Every radius is positive and each triangle stays inside the cone its three rays span, so the
// surface is closed, embedded (no self-intersections) and outward: det[x₀ x₁ x₂] keeps the sign
// of det[u₀ u₁ u₂] > 0 under positive radial scaling. Random numbers come from SplitMix64 seeded
// with `seed`, drawn in a fixed order; only sin/cos/sqrt of the C library can differ in the
// last bit between machines. Throws InputError for a definition out of range.
SurfaceMesh random_particle(const ParticleDef& def);

}  // namespace asperity::geometry
