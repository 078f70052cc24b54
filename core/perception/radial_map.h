// Radial map: a disparity image collapsed to one range per image column (the paper's
// "maximum valid disparity per column"), keeping only points inside the robot's swept
// volume (between the floor and the robot's height).
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "core/geometry/pose2.h"
#include "core/robot/robot_interface.h"

namespace coopmap {

struct RadialMapConfig {
  double min_height = 0.15;        // m above the floor; lower points are floor
  double max_range = 4.0;          // m; farther returns count as "beyond range"
  int min_support = 3;             // pixels in a column that must agree with the chosen return
  double support_tolerance = 0.6;  // px of disparity for agreement
  double spike_ratio = 0.3;  // a column this much nearer than both agreeing neighbours is a spike
  double disparity_sigma = 0.12;  // px, stereo disparity noise used for range uncertainty

  void validate() const;  // throws std::invalid_argument naming the field
};

enum class RadialKind : uint8_t {
  kNone = 0,    // no valid return in the swept volume: nothing known along this column
  kHit = 1,     // an obstacle at `range`
  kBeyond = 2,  // valid returns only beyond max_range: free up to max_range
};

struct RadialReading {
  double bearing = 0.0;    // rad in the robot frame (CCW from +x)
  double range = 0.0;      // m in the floor plane from the sensor origin
  double sigma = 0.0;      // m, 1-sigma range uncertainty (grows with depth squared)
  double disparity = 0.0;  // px (reference baseline)
  RadialKind kind = RadialKind::kNone;
};

struct RadialMap {
  double stamp = 0.0;
  Pose2 odometry;                           // X_OR at capture
  Eigen::Vector2d sensor_origin{0.0, 0.0};  // reference camera in the robot frame (m)
  double max_range = 4.0;                   // m
  std::vector<RadialReading> readings;      // one per reference image column, left to right
};

// Builds the radial map of a disparity image (CV_32F, kInvalidDisparity = invalid).
RadialMap buildRadialMap(const cv::Mat& disparity, const RobotDescription& robot,
                         const RadialMapConfig& config, double stamp, const Pose2& odometry);

// Removes isolated near "spikes" (stereo mismatches) in place; returns how many.
int removeSpikes(RadialMap& map, double spike_ratio);

}  // namespace coopmap
