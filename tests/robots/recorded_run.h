// One short live run of a small world, recorded, shared by the replay tests: a robot drives
// forward and turns in a walled room for a few seconds of simulated time.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

#include "sim/runner/world_run.h"
#include "sim/runner/world_run_outputs.h"
#include "tests/support/test_world.h"

namespace coopmap::test_support {

// A temporary folder of this test process (tests may run in parallel), removed at exit.
inline const std::filesystem::path& testTempDir() {
  struct TempDir {
    std::filesystem::path path;
    TempDir()
        : path(std::filesystem::temp_directory_path() /
               ("coopmap_replay_test_" + std::to_string(::getpid()))) {
      std::filesystem::remove_all(path);
      std::filesystem::create_directories(path);
    }
    ~TempDir() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  };
  static const TempDir dir;
  return dir.path;
}

struct RecordedRun {
  std::string dir;       // the recording
  std::string live_out;  // the live run's outputs
  RunResult live;
};

inline constexpr const char* kRecordedRoom =
    R"(floor: {min: [-1, -2], max: [4, 2], texture: carpet}
walls:
  - {from: [-1, -2], to: [4, -2], thickness: 0.1, height: 2.5, texture: poster}
  - {from: [4, -2], to: [4, 2], thickness: 0.1, height: 2.5, texture: poster}
  - {from: [4, 2], to: [-1, 2], thickness: 0.1, height: 2.5, texture: poster}
  - {from: [-1, 2], to: [-1, -2], thickness: 0.1, height: 2.5, texture: poster}
boxes:
  - {center: [2.5, 0.8], size: [0.6, 0.6, 0.8], yaw_deg: 20, texture: wood}
)";

// Runs once per test program (the result is kept), in testTempDir().
inline const RecordedRun& recordedRun() {
  static const RecordedRun run = [] {
    const std::filesystem::path base = testTempDir() / "run";
    RunOptions o;
    const TestWorldFile world =
        writeTestWorld("recorded_room", kRecordedRoom, "[1.2, 0.0], [1.2, -0.8]");
    o.world_file = world.path();
    o.seed = 7;
    o.duration = 8.0;
    o.odometry = "drifting";
    RecordedRun r;
    r.dir = (base / "rec").string();
    r.live_out = (base / "live").string();
    o.record_dir = r.dir;
    r.live = runWorld(o);
    writeRunOutputs(r.live_out, r.live);
    return r;
  }();
  return run;
}

}  // namespace coopmap::test_support
