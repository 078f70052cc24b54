// `coopmap remap RUN --world W`: rebuilds a run's map from its traverse logs at a chosen
// trajectory (the poses the run logged, its corrected traverses, odometry or the ground
// truth) and scores it against the world's true occupancy. The same radial maps at the true
// poses say what stereo alone allows; at the corrected poses, what the pose errors cost.
#pragma once

#include <string>
#include <vector>

#include "core/geometry/pose2.h"
#include "core/mapping/grid.h"
#include "core/mapping/map_metrics.h"
#include "core/perception/radial_map.h"
#include "core/sharing/shared_map.h"

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
  // The map's band, as OccupancyConfig::sigma_scale: the published shared map's by default
  // (`coopmap run --published-band`), 1 for the band the robots' own maps have.
  double band = kPublishedSigmaScale;
  // With poses "groundtruth": also the radial maps' range errors against the world's true
  // surfaces, by range (is the stereo's modelled range sigma what the ranges show?).
  bool range_errors = false;
};

// The range errors of radial-map returns (measured range minus the true surface's along
// the same ray) whose measured range falls in [from_m, to_m).
struct RangeErrorBin {
  double from_m = 0.0, to_m = 0.0;
  size_t returns = 0;   // hit returns in the bin
  size_t outliers = 0;  // of them, no true surface within max_error_m of the range
  // Over the rest (the inliers):
  double median_m = 0.0;
  double robust_sd_m = 0.0;   // 1.4826 x the median absolute deviation from the median
  double rms_m = 0.0;         // about zero
  double mean_sigma_m = 0.0;  // the returns' modelled 1-sigma (RadialReading::sigma)
  double within_sigma = 0.0;  // share with |error| <= their sigma (0.68 if it were right)
};

// One radial map at its true pose (the map frame of `truth`).
struct TrueScan {
  const RadialMap* scan = nullptr;
  Pose2 pose;
};

// Range errors of the hit returns of `scans` against the true occupancy `truth` (1:
// occupied; a fine grid, e.g. 1 cm, so that its cells' size does not add to the errors),
// in bins of `bin_m` by measured range. A return whose ray meets no occupied cell within
// `max_error_m` of its range (nearer or farther) is an outlier (a person, a phantom).
std::vector<RangeErrorBin> rangeErrors(const std::vector<TrueScan>& scans, const GridU8& truth,
                                       double bin_m = 1.0, double max_error_m = 0.5);

struct RemapSummary {
  std::vector<std::string> robots;
  size_t entries = 0;        // radial maps in the logs
  size_t without_pose = 0;   // of them, with no pose of that stamp in the trajectory
  size_t too_far = 0;        // of them, more than max_error_m from the ground truth
  size_t without_truth = 0;  // of them, with --oracle, with no ground-truth pose of that stamp
  size_t used = 0;
  MapMetrics metrics;  // against the world's true occupancy, as `coopmap run` scores
  std::vector<RangeErrorBin> range_errors;  // with RemapOptions::range_errors
};

// `pose` with the part RemapOptions::oracle names taken from `truth`; `pose` for "". Throws
// std::invalid_argument for another name.
Pose2 oraclePose(const Pose2& pose, const Pose2& truth, const std::string& oracle);

// Throws std::invalid_argument for bad options, std::runtime_error for unreadable or
// corrupt inputs (naming the file).
RemapSummary runRemap(const RemapOptions& options);

// Prints `summary` (of `runRemap(options)`) to stdout.
void printRemapSummary(const RemapOptions& options, const RemapSummary& summary);

}  // namespace coopmap
