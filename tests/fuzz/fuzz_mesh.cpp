// libFuzzer target: one mesh reader (solver/geometry/read_mesh.cpp), chosen at build time by
// ASPERITY_FUZZ_EXTENSION (".stl", ".obj", ".ply" or ".off"). Any input must end in a polygon
// soup or an InputError; anything else (a crash, a sanitizer report, std::bad_alloc from a
// trusted header count) is a defect.
#include <cstddef>
#include <cstdint>

#include "solver/core/error.hpp"
#include "solver/geometry/read_mesh.hpp"
#include "tests/fuzz/fuzz_input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    asperity::geometry::read_mesh_file(
        asperity::fuzz::write_input(data, size, ASPERITY_FUZZ_EXTENSION));
  } catch (const asperity::InputError&) {
  }
  return 0;
}
