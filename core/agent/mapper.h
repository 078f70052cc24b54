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
  MapperTiming timing_;
};

}  // namespace coopmap
