// libFuzzer target: the study definition (study/study_def.cpp). Any input must end in
// a StudyDef or an InputError; anything else is a defect.
#include <cstddef>
#include <cstdint>

#include "solver/core/error.hpp"
#include "study/study_def.hpp"
#include "tests/fuzz/fuzz_input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    asperity::study::load_study(asperity::fuzz::write_input(data, size, ".json"));
  } catch (const asperity::InputError&) {
  }
  return 0;
}
