// libFuzzer target: the robot model loader (robots/robot_model.h), on robot-file text.
#include <cstddef>
#include <cstdint>
#include <string>

#include "bench/fuzz/fuzz_input.h"
#include "robots/robot_model.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  coopmap::fuzz::expectCleanError([&] {
    coopmap::parseRobotModel(text, std::string(COOPMAP_SOURCE_DIR) + "/robots/fuzz/robot.yaml");
  });
  return 0;
}
