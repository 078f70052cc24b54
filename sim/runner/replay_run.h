// `coopmap replay DIR --out OUT`: the robots' agents run again on a coopmap recording
// (`coopmap run --record`), played through the robot interface control step by control step
// on the recording's clock. A recording cannot be steered: the agents decide as they did
// live (observe-only), their commands go nowhere, and with the same stream, teammates and
// shared map they map and log what the live run did, bit for bit. Version 1 recordings (no
// agent) are mapped by a mapper alone.
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
  std::vector<std::string> log;  // the agent's lines for people
  Pose2 odometry_in_map;         // where its first look placed the odometry (drawing)
};

struct ReplayResult {
  RecordingInfo info;
  std::vector<ReplayRobotResult> robots;
  double wall_time_s = 0.0;
};

// Replays every robot of the recording through a ReplayRobot and its agent; then, when
// options.out_dir is set, writes per robot what a live run writes (map_<robot>.{pgm,yaml,
// png}, map_<robot>_evaluation.png with recorded true occupancy, trajectory_<robot>_
// {groundtruth,odometry}.tum, traverse_<robot>.traverse) and a metrics.json, each atomically.
// Nothing is written unless the whole recording reads: a missing, corrupt or truncated file
// throws std::runtime_error naming the file and frame, as does a recording whose frames the
// agents do not take as the live ones did.
ReplayResult runReplay(const ReplayOptions& options);

}  // namespace coopmap
