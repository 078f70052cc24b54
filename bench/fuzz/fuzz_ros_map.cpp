// libFuzzer target: the map reader (core/mapping/ros_map.h), on a map_server YAML file and
// its image (see fuzz_input.h for how one input holds both).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "bench/fuzz/fuzz_input.h"
#include "core/mapping/ros_map.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto files =
      coopmap::fuzz::splitFiles(std::string_view(reinterpret_cast<const char*>(data), size));
  const auto dir = coopmap::fuzz::writeFiles(files);
  coopmap::fuzz::expectCleanError([&] { coopmap::loadRosMap((dir / "map.yaml").string()); });
  return 0;
}
