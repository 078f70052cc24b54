// libFuzzer target: the recording reader (robots/replay/recording.h), on a recording's
// text files (dataset.yaml, each robot's robot.yaml, agent.yaml and CSV files; see
// fuzz_input.h for how one input holds several files). Images are the map reader's part.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "bench/fuzz/fuzz_input.h"
#include "robots/replay/recording.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto files =
      coopmap::fuzz::splitFiles(std::string_view(reinterpret_cast<const char*>(data), size));
  const std::string dir = coopmap::fuzz::writeFiles(files).string();
  coopmap::fuzz::expectCleanError([&] {
    const coopmap::RecordingInfo info = coopmap::readRecordingInfo(dir);
    for (const coopmap::RecordedRobotInfo& robot : info.robots)
      coopmap::readRobotRecording(dir, info, robot);
  });
  return 0;
}
