// libFuzzer target: the scene loader (JSON parse + every key's checks). Any input must end in a
// SceneDef or an InputError; anything else (a crash, a sanitizer report, another exception) is a
// defect. docs/hostile.md says how to run it.
#include <cstddef>
#include <cstdint>
#include <string>

#include "solver/core/error.hpp"
#include "solver/io/json_file.hpp"
#include "solver/scene/scene_json.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const asperity::io::Json json = asperity::io::parse_json_text(text, "fuzz.json");
    asperity::scene::parse_scene(json, "fuzz.json", "");
  } catch (const asperity::InputError&) {
  }
  return 0;
}
