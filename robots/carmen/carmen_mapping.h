// `coopmap carmen LOG --out DIR`: the core on a recorded laser log in CARMEN format (the
// classic public robot data sets), played through the robot interface: an occupancy grid
// built from the scans at their odometry poses, its corner landmarks, the trajectory.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/io/tum.h"
#include "core/landmarks/corner_report.h"
#include "core/mapping/occupancy_grid.h"

namespace coopmap {

struct CarmenOptions {
  std::string log;           // CARMEN log file
  std::string out_dir;       // outputs go here (created if missing); empty: write nothing
  double resolution = 0.05;  // m per cell
  double max_range = 0.0;    // m, usable laser range; 0: the laser's own maximum
  int laser = 0;             // 1 front, 2 rear, 3, 4; 0: the lowest in the log
  double arm_length = 0.6;   // m, each arm of the corner model
  double margin = 0.5;       // m of map around everything the scans reach

  void validate() const;  // throws std::invalid_argument naming the option
};

struct CarmenResult {
  int scans = 0;                           // scans inserted
  int laser = 0;                           // the laser played
  double duration_s = 0.0;                 // first to last scan
  double path_length_m = 0.0;              // along the odometry track
  std::optional<OccupancyGrid> grid;       // the map
  CornersResult corners;                   // corners found in the map
  std::vector<StampedPose2> odometry;      // the odometry track
  std::vector<StampedPose2> ground_truth;  // TRUEPOS, when the log has it
  int occupied_cells = 0, free_cells = 0;
};

// Reads the log, maps it, finds corners; then, when options.out_dir is set, writes
// map.{pgm,yaml,png}, corners.{json,png}, trajectory_odometry.tum and (with TRUEPOS)
// trajectory_groundtruth.tum there, each atomically. Nothing is written unless the whole log
// reads and maps: a bad log throws CarmenLogError naming file, line and field.
CarmenResult runCarmen(const CarmenOptions& options);

}  // namespace coopmap
