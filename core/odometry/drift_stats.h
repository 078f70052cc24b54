// Odometry error statistics from a trajectory with ground truth: how the heading and
// distance errors of dead reckoning grow per metre driven and per radian turned. Used to
// fit simulator odometry presets to real logs and to check that simulated odometry
// reproduces them.
#pragma once

#include <string>
#include <vector>

#include "core/geometry/pose2.h"
#include "core/io/tum.h"

namespace coopmap {

// An odometry reading: forward and angular velocity from a timestamp on (m/s, rad/s).
struct VelocitySample {
  double stamp = 0.0;
  double v = 0.0;
  double w = 0.0;
};

// Dead reckoning of velocity samples from a start pose, sampled at `stamps` (each sample's
// velocity holds until the next sample).
std::vector<StampedPose2> integrateVelocities(const std::vector<VelocitySample>& odometry,
                                              const Pose2& start,
                                              const std::vector<double>& stamps);

struct DriftStats {
  int windows = 0;
  double window_s = 0.0;
  // Systematic parts, by least squares over windows:
  // heading error (true - odometry) = heading_bias_per_m * d + turn_bias * turned_signed.
  double heading_bias_per_m = 0.0;  // rad per metre driven
  double turn_bias = 0.0;           // rad per rad turned (signed)
  double scale_bias = 0.0;          // (odometry distance - true) / true distance
  // Random parts, variance growing linearly: var = s_m^2 * d + s_rad^2 * |turned|.
  double heading_sigma_per_sqrt_m = 0.0;                     // rad / sqrt(m)
  double heading_sigma_per_sqrt_rad = 0.0;                   // rad / sqrt(rad)
  double distance_sigma_per_sqrt_m = 0.0;                    // m / sqrt(m)
  double metres_per_window = 0.0, radians_per_window = 0.0;  // means, for context
};

// Windows of `window_s` seconds: in each, the odometry's relative motion is compared with
// the truth's. `truth` and `odometry` are sampled at the same stamps.
DriftStats driftStats(const std::vector<StampedPose2>& truth,
                      const std::vector<StampedPose2>& odometry, double window_s);

// Reads UTIAS MRCLAM files: "time x y theta" ground truth and "time v w" odometry ('#'
// comments). Throws std::runtime_error naming the file and line of a malformed row.
std::vector<StampedPose2> readUtiasGroundtruth(const std::string& path);
std::vector<VelocitySample> readUtiasOdometry(const std::string& path);

}  // namespace coopmap
