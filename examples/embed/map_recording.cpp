// Maps a coopmap recording with the installed core: every frame of every robot through its
// own mapper (trinocular stereo, radial map, occupancy grid at the frame's odometry), each
// robot's grid written as a ROS map. Usage: map_recording RECORDING OUT_DIR
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "core/agent/mapper.h"
#include "core/mapping/map_io.h"
#include "robots/replay/recording.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s RECORDING OUT_DIR\n", argv[0]);
    return 2;
  }
  const std::string dir = argv[1], out = argv[2];
  try {
    const coopmap::RecordingInfo info = coopmap::readRecordingInfo(dir);
    std::filesystem::create_directories(out);
    for (const coopmap::RecordedRobotInfo& robot : info.robots) {
      const coopmap::RobotRecording recording = coopmap::readRobotRecording(dir, info, robot);
      coopmap::Mapper mapper(recording.description, info.map, coopmap::MapperConfig{});
      for (size_t i = 0; i < recording.frames.size(); ++i)
        mapper.process(coopmap::readRecordedFrame(recording, i), recording.frames[i].segment);
      const coopmap::OccupancyGrid& grid = mapper.grid();
      int occupied = 0, free = 0;
      for (int iy = 0; iy < grid.limits().height; ++iy)
        for (int ix = 0; ix < grid.limits().width; ++ix) {
          occupied += grid.state(ix, iy) == coopmap::CellState::kOccupied;
          free += grid.state(ix, iy) == coopmap::CellState::kFree;
        }
      coopmap::writeRosMap(grid, out, "map_" + robot.name);
      std::printf("%s: %zu frames, %d occupied and %d free cells, map in %s/map_%s.yaml\n",
                  robot.name.c_str(), recording.frames.size(), occupied, free, out.c_str(),
                  robot.name.c_str());
      // A recording that holds frames maps something: an empty map is a failure.
      if (!recording.frames.empty() && (occupied == 0 || free == 0)) {
        std::fprintf(stderr, "%s: the map is empty\n", robot.name.c_str());
        return 1;
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
