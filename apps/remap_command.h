// `coopmap remap RUN --world W`: rebuilds a run's map from its traverse logs at a chosen
// trajectory (the poses the run logged, its corrected traverses, odometry or the ground
// truth) and scores it against the world's true occupancy. The same radial maps at the true
// poses say what stereo alone allows; at the corrected poses, what the pose errors cost.
#pragma once

#include <string>
#include <vector>

#include "core/geometry/pose2.h"
#include "core/mapping/map_metrics.h"

namespace coopmap {

struct RemapOptions {
  std::string run_dir;     // a `coopmap run` output folder: traverse_<robot>.traverse files
  std::string world_file;  // the world the run was in
  // logged (the poses in the traverse logs: the live estimate), corrected, estimate,
  // odometry or groundtruth (the run's trajectory_<robot>_<poses>.tum)
  std::string poses = "corrected";
  // > 0: only the radial maps whose pose is within this (m) of the ground truth, for an
  // oracle's choice of what to share
  double max_error_m = 0.0;
  // "position", "heading", "along" or "across": that part of each pose from the ground
  // truth, the rest from `poses` (which part of the pose error costs the map); "" (the
  // default): none. "along" and "across" split the position error by the true heading: the
  // part along the robot's travel (or facing), and the part across it.
  std::string oracle;
  std::string out_dir;  // if set: map.{pgm,yaml,png} and map_evaluation.png
};

struct RemapSummary {
  std::vector<std::string> robots;
  size_t entries = 0;        // radial maps in the logs
  size_t without_pose = 0;   // of them, with no pose of that stamp in the trajectory
  size_t too_far = 0;        // of them, more than max_error_m from the ground truth
  size_t without_truth = 0;  // of them, with --oracle, with no ground-truth pose of that stamp
  size_t used = 0;
  MapMetrics metrics;  // against the world's true occupancy, as `coopmap run` scores
};

// `pose` with the part RemapOptions::oracle names taken from `truth`; `pose` for "". Throws
// std::invalid_argument for another name.
Pose2 oraclePose(const Pose2& pose, const Pose2& truth, const std::string& oracle);

// Throws std::invalid_argument for bad options, std::runtime_error for unreadable or
// corrupt inputs (naming the file).
RemapSummary runRemap(const RemapOptions& options);

}  // namespace coopmap
