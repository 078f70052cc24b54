// One robot's mapping pipeline for a sensing cycle: trinocular stereo, radial map,
// occupancy grid update, with the radial maps kept for the traverse.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "core/correction/traverse_log.h"
#include "core/mapping/occupancy_grid.h"
#include "core/perception/radial_map.h"
#include "core/robot/robot_interface.h"
#include "core/stereo/trinocular_matcher.h"

namespace coopmap {

struct MapperConfig {
  StereoConfig stereo;
  RadialMapConfig radial;
  OccupancyConfig occupancy;
};

// Wall time spent per stage since construction (for real-time-factor reports).
struct MapperTiming {
  double stereo_s = 0.0;   // trinocular matching
  double mapping_s = 0.0;  // radial map and grid update
  int frames = 0;
};

class Mapper {
 public:
  Mapper(const RobotDescription& robot, const MapLimits& limits, const MapperConfig& config);

  // Runs one sensing cycle on a frame; the map is updated at the frame's odometry pose and
  // the radial map appended to the traverse log with the motion segment under way.
  // Returns the radial map it inserted.
  const RadialMap& process(const TrinocularFrame& frame,
                           MotionSegment segment = MotionSegment::kStop);

  const OccupancyGrid& grid() const { return grid_; }

  // The robot's pose estimate in the map frame is X_MO * odometry; identity at first (the
  // map frame is the odometry frame at the start). A home-base fix changes it: from then on
  // scans are inserted, and logged, at the corrected estimate.
  void setFrame(const Pose2& X_MO);
  const Pose2& frame() const { return frame_; }
  Pose2 estimate(const Pose2& odometry) const { return framed_ ? frame_ * odometry : odometry; }

  // Replaces the robot's map with an imported one (the shared map), same limits and rule.
  // Throws std::invalid_argument when the layers do not fit.
  void importMap(const std::vector<int16_t>& log_odds, const std::vector<uint8_t>& seen);
  // The odometry each traverse entry's frame carried (the log holds the estimate): the
  // odometry chain a sortie is corrected on. (The caller may hand the mapper calibrated
  // odometry; naive sharing keeps the encoders' own.)
  const std::vector<Pose2>& rawOdometry() const { return raw_odometry_; }
  const cv::Mat& lastDisparity() const { return disparity_; }
  const TraverseLog& traverse() const { return traverse_; }
  void setRobotName(const std::string& name) { traverse_.robot = name; }
  const StereoStats& lastStereoStats() const { return stats_; }
  const MapperTiming& timing() const { return timing_; }

 private:
  RobotDescription robot_;
  MapperConfig config_;
  TrinocularMatcher matcher_;
  OccupancyGrid grid_;
  cv::Mat disparity_;
  StereoStats stats_;
  TraverseLog traverse_;
  std::vector<Pose2> raw_odometry_;
  Pose2 frame_;
  bool framed_ = false;
  MapperTiming timing_;
};

}  // namespace coopmap
