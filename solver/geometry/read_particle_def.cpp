// The one reader of a generated particle's fields (random_particle.hpp). A file of its own: the
// study definition's reader needs it without the particle generator, and so does its fuzz
// target, which compiles study_def.cpp against the JSON reader alone (tests/fuzz/CMakeLists.txt).
#include <cstdint>
#include <limits>

#include "solver/geometry/random_particle.hpp"
#include "solver/io/json_file.hpp"

namespace asperity::geometry {

ParticleDef read_particle_def(const io::JsonReader& r) {
  ParticleDef d;
  d.seed = static_cast<std::uint64_t>(r.integer("seed", 0, std::numeric_limits<long long>::max()));
  d.size = r.number_or("size", d.size);
  d.elongation = r.number_or("elongation", d.elongation);
  d.flatness = r.number_or("flatness", d.flatness);
  d.angularity = r.number_or("angularity", d.angularity);
  d.roughness = r.number_or("roughness", d.roughness);
  if (r.has("faces")) d.faces = static_cast<long>(r.integer("faces", 20, 2'000'000));
  return d;
}

}  // namespace asperity::geometry
