// `coopmap replay DIR --out OUT`: the core on a coopmap recording (`coopmap run --record`),
// played through the robot interface: the same mapper, configuration and motion-segment
// labels as the live run, and the same outputs.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/correction/traverse_log.h"
#include "core/io/tum.h"
#include "core/mapping/map_metrics.h"
#include "core/mapping/occupancy_grid.h"
#include "robots/replay/recording.h"

namespace coopmap {

struct ReplayOptions {
  std::string recording;  // recording folder
  std::string out_dir;    // outputs go here (created if missing); empty: write nothing
};

struct ReplayRobotResult {
  std::string name;
  int frames = 0;
  double duration_s = 0.0;                 // first to last frame
  double odometry_path_length_m = 0.0;     // along the recorded odometry
  std::optional<double> path_length_m;     // true distance driven, with ground truth
  std::optional<double> odometry_error_m;  // final |odometry - truth|, with ground truth
  std::optional<double> odometry_error_deg;
  std::optional<MapMetrics> map;  // with the recorded true occupancy and start pose
  std::vector<StampedPose2> groundtruth, odometry;
  TraverseLog traverse;
  std::optional<OccupancyGrid> grid;
};

struct ReplayResult {
  RecordingInfo info;
  std::vector<ReplayRobotResult> robots;
  double wall_time_s = 0.0;
};

// Replays every robot of the recording through a ReplayRobot and a Mapper with the live
// run's configuration; then, when options.out_dir is set, writes per robot what a live run
// writes (map_<robot>.{pgm,yaml,png}, map_<robot>_evaluation.png with recorded true
// occupancy, trajectory_<robot>_{groundtruth,odometry}.tum, traverse_<robot>.traverse) and a
// metrics.json, each atomically. Nothing is written unless the whole recording reads: a
// missing, corrupt or truncated file throws std::runtime_error naming the file and frame.
ReplayResult runReplay(const ReplayOptions& options);

}  // namespace coopmap
