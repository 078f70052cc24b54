// libFuzzer target: the world loader (sim/world/world.h), on world-file text. Robot model
// paths resolve against worlds/ of the source tree, as for the project's own worlds.
#include <cstddef>
#include <cstdint>
#include <string>

#include "bench/fuzz/fuzz_input.h"
#include "sim/world/world.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  coopmap::fuzz::expectCleanError([&] {
    coopmap::sim::parseWorld(text, std::string(COOPMAP_SOURCE_DIR) + "/worlds/fuzz.yaml");
  });
  return 0;
}
