// Trajectory error against ground truth: absolute trajectory error (no alignment: both are
// in the map frame the home base defines) and KITTI-style relative drift over sub-paths
// of fixed lengths.
#pragma once

#include <vector>

#include "core/geometry/pose2.h"

namespace coopmap {

struct TrajectoryError {
  double ate_rmse_m = 0.0;  // RMS position error over all poses (m)
  double ate_max_m = 0.0;   // worst position error (m)
  // ATE after the best uniform scaling of the estimate about its first pose: what is left
  // once a distance-scale error (unobservable on a loop that closes at home) is taken out.
  double ate_scale_aligned_m = 0.0;
  double scale = 1.0;             // that scaling
  double heading_rmse_deg = 0.0;  // RMS heading error (deg)
  double drift_percent = 0.0;     // mean translational error per sub-path length (%)
  double drift_deg_per_m = 0.0;   // mean rotational error per metre of sub-path
  int subpaths = 0;               // sub-paths the drift is averaged over
};

// Compares poses `estimate[i]` with `truth[i]` (same length, same stamps). Sub-paths start
// every `stride_m` of true path length and run `lengths_m` metres (KITTI's odometry metric
// on the scale of a building: 5, 10, 20, 40 m by default; lengths longer than the path are
// skipped). Throws std::invalid_argument if the lengths differ.
TrajectoryError trajectoryError(const std::vector<Pose2>& estimate, const std::vector<Pose2>& truth,
                                const std::vector<double>& lengths_m = {5.0, 10.0, 20.0, 40.0},
                                double stride_m = 1.0);

}  // namespace coopmap
