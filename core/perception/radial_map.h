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
  // Beyond the paper: a column with no return of its own whose view of the floor ends
  // nearer than this depth (m) has met something the cameras cannot match (a textureless
  // wall): a return at the floor's end. Open floor stays matchable to about 1.6 m with the
  // B-14's 160 x 120 cameras 0.9 m up (nearer than about 1.22 m they do not see the floor),
  // so only a nearer end says "occluded"; 1.5 m suits them. 0: off (the default: in a room
  // whose walls all have texture it only adds the floor ends' errors; measured in
  // docs/experiments/2026-12-building-settings.md; the agents use 1.5).
  double floor_edge_depth = 0.0;
  double floor_tolerance = 0.5;  // px: a pixel is floor when its disparity is the floor's +- this
  // m, 1-sigma range uncertainty of a floor's end at least (on rendered frames it fell 2 cm
  // nearer to 11 cm farther than the wall): free space is marked only up to its uncertainty
  // region, so a floor's end placed too far does not clear what stereo saw there.
  double floor_edge_sigma = 0.08;
  // Beyond the paper: pixels beyond max_range in a column, agreeing within
  // support_tolerance, that make it "free to max_range" (kBeyond). 1, the default: any one
  // (the paper's rule). On a textureless wall seen at a grazing angle a stray mismatch or
  // two beyond max_range clears the wall's whole length behind it; the building's plaster
  // wall is drawn with 3 (as min_support for a hit). In a room whose walls all have texture
  // a far view seen by only a pixel or two is mostly a true one, and 3 there made the maps
  // worse (measured in docs/experiments/2026-12-building-settings.md; the agents use 3).
  int beyond_support = 1;

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
  // A kHit placed where the floor's view ends (floor_edge_depth), not on a matched surface:
  // its range is the floor's, biased by how far the unmatched wall's foot hides it.
  bool floor_edge = false;
};

struct RadialMap {
  double stamp = 0.0;
  Pose2 odometry;                           // X_OR at capture
  Eigen::Vector2d sensor_origin{0.0, 0.0};  // reference camera in the robot frame (m)
  double max_range = 4.0;                   // m
  std::vector<RadialReading> readings;      // one per reference image column, left to right
};

// Builds the radial map of a disparity image (CV_32F, kInvalidDisparity = invalid). The
// floor is taken as level, at the rig's mount height below the reference camera.
RadialMap buildRadialMap(const cv::Mat& disparity, const RobotDescription& robot,
                         const RadialMapConfig& config, double stamp, const Pose2& odometry);

// Removes isolated near "spikes" (stereo mismatches) in place; returns how many.
int removeSpikes(RadialMap& map, double spike_ratio);

}  // namespace coopmap
