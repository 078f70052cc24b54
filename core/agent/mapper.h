// One robot's mapping pipeline for a sensing cycle: trinocular stereo, radial map,
// occupancy grid update, with the radial maps kept for the traverse.
#pragma once

#include <optional>
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
  // Also match every frame on centred windows and keep that radial map beside the logged
  // one (centredScans): for a measurement of distance along the travel (the distance scale
  // from stereo), which shifted windows lengthen as they move the edges of thin jambs and
  // corners. The grid and the traverse log take the configured windows' scans.
  bool centred_scans = false;
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
  // Returns the radial map as seen, teammates included (for safety: a teammate close ahead
  // must stop the robot, though it is not mapped). A look at the home base
  // (`home_base_look`) is matched on centred windows whatever the configuration's
  // window_shift: the corners' fits were made for them, and shifted windows move the edges
  // of the landmarks' thin arms.
  const RadialMap& process(const TrinocularFrame& frame,
                           MotionSegment segment = MotionSegment::kStop,
                           bool home_base_look = false);

  const OccupancyGrid& grid() const { return grid_; }

  // The robot's pose estimate in the map frame is X_MO * odometry; identity at first (the
  // map frame is the odometry frame at the start). A home-base fix changes it: from then on
  // scans are inserted, and logged, at the corrected estimate.
  void setFrame(const Pose2& X_MO);
  // Places everything mapped so far in the frame X_MO: the estimate's frame becomes X_MO, each
  // traverse entry moves to X_MO * its odometry (rawOdometry) and is masked for the teammates
  // set now, and the grid is built again from the entries. For the looks at the start, which
  // place the odometry frame in the map frame; until keepPlacement().
  void relocate(const Pose2& X_MO);
  // The placement is final: relocate() is no longer allowed (and what it needs is dropped).
  void keepPlacement();
  // Masks the logged entries from `from` on for the teammates set now (see setTeammates): a
  // teammate placed after the robot logged where it stood is left out afterwards.
  void maskLogged(size_t from);
  const Pose2& frame() const { return frame_; }
  Pose2 estimate(const Pose2& odometry) const { return framed_ ? frame_ * odometry : odometry; }

  // Replaces the robot's map with an imported one (the shared map), same limits and rule.
  // Throws std::invalid_argument when the layers do not fit.
  void importMap(const std::vector<int16_t>& log_odds, const std::vector<uint8_t>& seen);
  // The odometry each traverse entry's frame carried (the log holds the estimate): the
  // odometry chain a sortie is corrected on. (The caller may hand the mapper calibrated
  // odometry; naive sharing keeps the encoders' own.)
  const std::vector<Pose2>& rawOdometry() const { return raw_odometry_; }
  // Where the teammates are (map frame, as they report themselves), for the next frames:
  // a return within `radius` of one is the teammate, not the world, and is left out of the
  // traverse log (what is posted to the shared map, where it would be a phantom obstacle, and
  // what the home-base fixes are made from, where it would be a moving one). The logged
  // column stays free up to the teammate's edge. The robot's own map, which it drives by,
  // keeps the teammate where it is seen (a report may be off by the teammate's drift).
  // An empty list or radius 0: nothing masked.
  void setTeammates(std::vector<Eigen::Vector2d> positions, double radius);
  int maskedReturns() const { return masked_; }  // returns left out so far
  const cv::Mat& lastDisparity() const { return disparity_; }
  const TraverseLog& traverse() const { return traverse_; }
  // With centred_scans: each traverse entry's radial map as centred windows match its frame
  // (the same map where the frame was matched on centred windows), at the entry's pose and
  // masked as the entry is; one per entry, in order. Empty otherwise.
  const std::vector<RadialMap>& centredScans() const { return centred_; }
  void setRobotName(const std::string& name) { traverse_.robot = name; }
  const StereoStats& lastStereoStats() const { return stats_; }
  const MapperTiming& timing() const { return timing_; }

 private:
  RobotDescription robot_;
  // Leaves the returns within the teammates' discs out of `scan` (taken at `pose`).
  void maskTeammates(RadialMap& scan, const Pose2& pose);
  MapperConfig config_;
  TrinocularMatcher matcher_;
  std::optional<TrinocularMatcher> look_matcher_;  // centred, when matcher_'s windows shift
  OccupancyGrid grid_;
  cv::Mat disparity_;
  StereoStats stats_;
  TraverseLog traverse_;
  std::vector<Pose2> raw_odometry_;
  Pose2 frame_;
  bool framed_ = false;
  RadialMap last_scan_;                      // unmasked
  std::vector<RadialMap> unmasked_;          // every entry's scan as seen, for relocate
  std::vector<RadialMap> centred_;           // centred_scans: one per entry, masked
  std::vector<RadialMap> unmasked_centred_;  // ... as seen, for relocate
  cv::Mat centred_disparity_;
  bool placement_kept_ = false;
  std::vector<Eigen::Vector2d> teammates_;
  double teammate_radius_ = 0.0;
  int masked_ = 0;
  MapperTiming timing_;
};

}  // namespace coopmap
