// The mission's obstacle memory (core/agent/mission.h): what its planning must keep clear, or
// may take as free, beyond what the robot's map holds. Where its cameras have just seen
// something (recent_hits_s), where its bumpers touched something this sortie, and where its
// body has been (free though the cameras never see beneath the robot), with the trail of this
// sortie (trail_after_waits). From these, the robot's map and its teammates, it builds the
// conservative map the mission plans on. Positions are in the frame of the pose estimate,
// like the robot's map.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "core/agent/mission_config.h"
#include "core/mapping/occupancy_grid.h"
#include "core/perception/radial_map.h"
#include "core/planning/planning_map.h"

namespace coopmap {

// How a planning map is built (ObstacleMemory::planningMap).
struct PlanningMapOptions {
  bool allow_unknown = false;  // unknown cells count as free
  // What the cameras have just seen blocks too (recent_hits_s), but for what is so near the
  // robot that it could not start (that is the safety stop's and the bumpers').
  bool recent = true;
  double margin = -1.0;  // m beyond the robot's radius, instead of planning.margin (< 0: that)
  bool trail = false;    // the cells along this sortie's trail are free (trail_after_waits)
};

// The least margin that keeps the body off every blocked cell: sqrt(2) cells (m).
inline double leastMargin(const MapLimits& lim) { return std::sqrt(2.0) * lim.resolution; }

class ObstacleMemory {
 public:
  explicit ObstacleMemory(const MissionConfig& config);

  // The robot's body covers the cells around `odometry` now: visited, and on this sortie's
  // trail. Sized to `map`'s limits on first use.
  void markVisited(const OccupancyGrid& map, const Pose2& odometry);
  // Adds the scan's hits within recent_hits_range, taken at `odometry` at `now` (s), and drops
  // those older than recent_hits_s; returns how many it added (0 when recent_hits_s is off).
  size_t rememberHits(double now, const Pose2& odometry, const RadialMap& scan);
  // The bumpers touched something at `bearing` (rad, robot frame) from the robot at
  // `odometry`: an obstacle where it touched, spread across the bearing over bump_width.
  void addBump(const Pose2& odometry, double bearing);
  // One of the last `fresh` hits remembered lies within the planning clearance of `way`
  // (a polyline from the robot, map frame).
  bool freshHitNear(const std::vector<Eigen::Vector2d>& way, size_t fresh) const;
  // One of the hits remembered lies nearer than `distance` (m) to the cameras of the robot
  // at `odometry`, within `half_angle` (rad) of straight ahead, and no later radial map saw
  // past it: what the safety stop sees in the latest radial map, kept while it is remembered
  // (recent_hits_s) and out of the cameras' sight (nearer than they see, or beside them).
  bool recentHitAhead(const Pose2& odometry, double distance, double half_angle) const;
  bool hasRecentHits() const { return !recent_.empty(); }
  bool hasTrail() const { return !trail_.cells.empty(); }

  // The map to plan on: `map`, with the cells the robot has been on free (unless held firmly
  // occupied), and what the cameras have just seen, what the bumpers touched and the
  // teammates (map frame, discs of team_radius) blocked. `robot`: where it stands now.
  PlanningMap planningMap(const OccupancyGrid& map, const Eigen::Vector2d& robot,
                          const std::vector<Eigen::Vector2d>& teammates,
                          const PlanningMapOptions& options) const;

  // A new sortie after a fix: the estimate's frame changed, so the bumps, the recent hits
  // and the trail are forgotten. The visited cells stay.
  void startSortie();
  // The robot was placed in the map frame: all that was kept in the odometry frame goes.
  void clear();

 private:
  // Marks the hits remembered that `scan`, taken at `odometry`, sees past.
  void markSeenThrough(const Pose2& odometry, const RadialMap& scan);

  struct RecentHit {
    double t;           // s
    int frame;          // counts the scans remembered
    Eigen::Vector2d p;  // map frame (the estimate's)
    // A later radial map saw past it (a hit beyond it, or free beyond it, in its column):
    // nothing stands there now, though the planning keeps it for recent_hits_s.
    bool seen_through = false;
  };

  MissionConfig config_;
  std::vector<Eigen::Vector2d> bumps_;  // where the bumpers touched something this sortie
  int recent_frames_ = 0;
  std::vector<RecentHit> recent_;            // hits of the last recent_hits_s, oldest first
  Eigen::Vector2d sensor_origin_{0.0, 0.0};  // the cameras' (robot frame), from the scans
  GridU8 visited_;  // cells the robot's body has covered: free, seen or not
  GridU8 trail_;    // this sortie's: see trail_after_waits
};

// The maps the mission plans on, built on demand: borrows the robot's map, the memory and the
// teammates' positions for as long as it lives (one update).
class PlanningMaps {
 public:
  PlanningMaps(const OccupancyGrid& map, const ObstacleMemory& memory, const Eigen::Vector2d& robot,
               const std::vector<Eigen::Vector2d>& teammates)
      : map_(map), memory_(memory), robot_(robot), teammates_(teammates) {}

  PlanningMap operator()(const PlanningMapOptions& options = {}) const {
    return memory_.planningMap(map_, robot_, teammates_, options);
  }
  const OccupancyGrid& map() const { return map_; }
  const ObstacleMemory& memory() const { return memory_; }

 private:
  const OccupancyGrid& map_;
  const ObstacleMemory& memory_;
  Eigen::Vector2d robot_;
  const std::vector<Eigen::Vector2d>& teammates_;
};

}  // namespace coopmap
