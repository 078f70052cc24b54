// The mission's dealings with teammates on the move (core/agent/mission.h): where they are
// and how fast they go, a teammate in the way ahead (or, for the robot without priority,
// converging on its way from the side), and passages (doors) taken one robot at a time. It
// says when to stop and wait for a teammate, and when the wait for one ahead is over and the
// robot should plan around it.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "core/agent/mission_config.h"
#include "core/geometry/pose2.h"
#include "core/mapping/occupancy_grid.h"

namespace coopmap {

// Whether to wait for a teammate (TeamTraffic::passageWait, TeamTraffic::teammateWait).
enum class TeamWait {
  kNone,      // drive on
  kNewWait,   // stop: a wait begins now
  kWaiting,   // stop: still waiting
  kWaitOver,  // waited long enough for the teammate ahead: plan around it
};

class TeamTraffic {
 public:
  explicit TeamTraffic(const MissionConfig& config);

  // Where the teammates are now (map frame, as they report it) and whether this robot has
  // the right of way over them.
  void set(std::vector<Eigen::Vector2d> positions, bool priority);
  const std::vector<Eigen::Vector2d>& positions() const { return positions_; }
  // Takes the teammates' velocities over the last team_velocity_s, at `now` (s).
  void track(double now);

  // The robot at `pose`, its way ahead `way` (a polyline from it, map frame) on `map`;
  // `driving`: it drives forwards along a route. Whether to wait at `now` (s) for a teammate
  // in or at the passage ahead (passage_width): until it is through and away, at most
  // passage_wait_s (then not again for as long). Never kWaitOver.
  TeamWait passageWait(double now, const Pose2& pose, const std::vector<Eigen::Vector2d>& way,
                       const OccupancyGrid& map, bool driving);
  // As passageWait, for a teammate in the way (teammateInTheWay) at `linear` m/s: wait
  // team_wait_s (a quarter of it with priority), then plan around it.
  TeamWait teammateWait(double now, const Pose2& pose, const std::vector<Eigen::Vector2d>& way,
                        double linear, bool driving);

  int teamStops() const { return team_stops_; }
  int passageWaits() const { return passage_waits_; }

 private:
  bool teammateAhead(const Pose2& pose, const std::vector<Eigen::Vector2d>& way) const;
  // A teammate ahead, or (without priority) one converging on this robot's way.
  bool teammateInTheWay(const Pose2& pose, const std::vector<Eigen::Vector2d>& way,
                        double linear) const;
  // The first place within passage_lookahead along the way where it runs through a passage
  // (see passage_width), if any; `here` says whether the robot stands in it now.
  std::optional<Eigen::Vector2d> passageAhead(const std::vector<Eigen::Vector2d>& way,
                                              const OccupancyGrid& map, bool* here) const;
  // A teammate holds the passage ahead: wait for it (passage_width).
  bool passageHeld(const Pose2& pose, const std::vector<Eigen::Vector2d>& way,
                   const OccupancyGrid& map) const;

  MissionConfig config_;
  std::vector<Eigen::Vector2d> positions_;
  bool priority_ = false;
  // Where the teammates were team_velocity_s ago, and their velocities since (map frame).
  std::vector<Eigen::Vector2d> positions_before_;
  std::vector<Eigen::Vector2d> velocities_;
  double positions_before_at_ = -1.0;
  double team_wait_until_ = -1.0;  // waiting for a teammate ahead until then
  int team_stops_ = 0;
  double passage_wait_since_ = -1.0;  // waiting for a passage since then
  double passage_next_ = -1.0;        // after a wait that timed out: no waiting until then
  int passage_waits_ = 0;
};

}  // namespace coopmap
