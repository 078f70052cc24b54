// The per-robot outputs of a run, shared by a live run (`coopmap run`), a replay (`coopmap
// replay`) and a real robot's (`coopmap robot`), so all write the same files the same way.
#pragma once

#include <string>
#include <vector>

#include "core/correction/traverse_log.h"
#include "core/io/tum.h"
#include "core/mapping/grid.h"
#include "core/mapping/occupancy_grid.h"

namespace coopmap {

// What one robot's outputs are made of; pointers are borrowed for the call.
struct RobotOutputs {
  std::string name;
  std::string world;  // world name, for the trajectory files' comments
  const OccupancyGrid* grid = nullptr;
  const std::vector<StampedPose2>* groundtruth = nullptr;  // null or empty: none
  const std::vector<StampedPose2>* odometry = nullptr;
  const GridU8* truth = nullptr;  // true occupancy over the grid's limits; null: none
  const TraverseLog* traverse = nullptr;
  Pose2 odometry_in_map;  // X_MO: where the odometry is drawn over the map
};

// Writes into `dir` (which must exist), each file atomically: map_<name>.{pgm,yaml,png}
// (ground truth drawn green, odometry red),
// map_<name>_evaluation.png (with truth), trajectory_<name>_groundtruth.tum (with ground
// truth), trajectory_<name>_odometry.tum and traverse_<name>.traverse.
void writeRobotOutputs(const std::string& dir, const RobotOutputs& r);

// A run folder's traverse_<robot>.traverse logs, sorted by robot name.
struct RunLog {
  std::string robot;
  std::string path;
  // The folder's trajectory_<robot>_<kind>.tum (kind: groundtruth, odometry, corrected, ...).
  std::string trajectory(const std::string& kind) const;
};
// Throws std::runtime_error naming the folder if it cannot be read.
std::vector<RunLog> runLogsIn(const std::string& dir);

}  // namespace coopmap
