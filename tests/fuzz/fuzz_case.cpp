// libFuzzer target: a validation case file (validation/case_load.cpp: the case's keys, its scene,
// its expected values and their analytic references). Any input must end in a CaseDef or an
// InputError; anything else is a defect.
#include <cstddef>
#include <cstdint>

#include "solver/core/error.hpp"
#include "tests/fuzz/fuzz_input_file.hpp"
#include "validation/case.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    asperity::validation::load_case(asperity::fuzz::write_input(data, size, ".json"));
  } catch (const asperity::InputError&) {
  }
  return 0;
}
