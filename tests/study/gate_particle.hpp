// The generated particle both source-reference tests use (test_source_reference.cpp's gate,
// test_source_reference_terms.cpp's plan): a seed outside data/particles/set.json (its seeds are
// 1000-1049) with the set's ballast-like shape numbers, written once so the two stay one particle.
#pragma once

#include "solver/geometry/random_particle.hpp"

namespace asperity::study::test {

// `faces` source triangles: the set's 20 480 unless a test asks for a coarser source.
inline SurfaceMesh gate_particle_7321(long faces = 20480) {
  return geometry::random_particle({.seed = 7321,
                                    .size = 0.05,
                                    .elongation = 0.8,
                                    .flatness = 0.8,
                                    .angularity = 0.8,
                                    .roughness = 0.15,
                                    .faces = faces});
}

}  // namespace asperity::study::test
