// A robot's mission (section 4 of the paper, autonomous): look at the home base, explore
// the frontiers of its own map with planned paths, keep itself safe, come home when the
// budget is spent or nothing reachable is left, and look at the home base again (the data
// the home-base protocol needs to correct the traverse). Robot-agnostic: it turns the pose
// estimate, the robot's map and its latest radial map into motion commands. Until the first
// look places the robot in the map frame (startFrom) it works in the odometry frame.
//
// MissionAgent holds the phases and the route being driven; its update is a short policy over
// parts that each keep one concern's state: the safety governor (safety_governor.h), the
// obstacle memory and the maps planned on (obstacle_memory.h), goal selection
// (exploration_goals.h), the way home (homing.h) and teammates on the move (team_traffic.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/agent/exploration_goals.h"
#include "core/agent/homing.h"
#include "core/agent/mission_config.h"
#include "core/agent/obstacle_memory.h"
#include "core/agent/route_follower.h"
#include "core/agent/safety_governor.h"
#include "core/agent/team_traffic.h"
#include "core/mapping/occupancy_grid.h"
#include "core/perception/radial_map.h"
#include "core/planning/frontiers.h"
#include "core/planning/path_planner.h"
#include "core/planning/planning_map.h"

namespace coopmap {

// kLookAtHome: the first look, at the start; kAtStart: waiting for the caller to place the
// robot in the map frame by that look (startFrom, or lookAgainAtStart).
enum class MissionPhase { kLookAtHome, kAtStart, kExplore, kReturn, kLookAgain, kAtHome, kDone };
const char* toString(MissionPhase p);

class MissionAgent {
 public:
  // `home`: where the first look is taken (the start, odometry frame).
  MissionAgent(const Pose2& home, const MissionConfig& config);

  // In phase kAtStart: the first look placed the robot in the map frame; `home` is its start
  // there (map frame, as every pose given to update from now on). Explore (phase kExplore).
  // Called before (phase kLookAtHome: the robot was placed beforehand), it explores as soon
  // as the look is over.
  void startFrom(const Pose2& home, double now);
  // In phase kAtHome: the robot's start in the map frame moved (its frame was aligned to the
  // team's): the home it comes back to from now on.
  void moveHome(const Pose2& home);
  // In phase kAtStart: drive to `look` (the map frame's, as every pose given to update from
  // now on) and take the look there (phase kLookAtHome, then kAtStart again).
  void lookFrom(const Waypoint& look);
  // In phase kAtStart: the look found no home base; turn again where it stands.
  void lookAgainAtStart();

  // The command for now (s), given the odometry pose, the robot's map (odometry frame) and
  // the latest radial map (nullptr if none since the last call), and whether the bumpers
  // touch something (then it backs off and gives the goal up) and at what bearing (rad, robot
  // frame) if the base says.
  MotionCommand update(double now, const Pose2& odometry, const OccupancyGrid& map,
                       const RadialMap* latest, bool bumped = false,
                       std::optional<double> bump_bearing = std::nullopt);

  // In phase kAtHome: the caller has dealt with the sortie; go again (phase kExplore) unless
  // exploration is complete or the sorties are spent (phase kDone). The robot's pose
  // estimate may have jumped (a home-base fix): the next update's pose is taken as it is.
  void continueAfterFix(double now);
  // In phase kAtHome: drive to `home` (the home pose as the robot's estimate now places it:
  // a fix showed the estimate off) and look again there, then wait in kAtHome once more.
  // After a look taken where the robot stood because the way home was blocked, with home
  // where it was (no fix moved it), the look again is taken there too: the same way home
  // would meet the same blockage.
  void returnAgain(const Pose2& home);
  // Ends the mission where the robot is (e.g. it could not be localized at home: it no
  // longer knows where it is, and exploring on would only drive it into things).
  // `position_known` false says so: its estimate is no longer where it stands (lost()).
  void finish(const std::string& reason, bool position_known = true);
  // Stopped for good without knowing where it is: teammates should not trust the position
  // it reports (not keep clear of it there, not leave it out of their maps there) but see it
  // as whatever else stands in their way.
  bool lost() const { return lost_; }
  int sortie() const { return sortie_; }  // 1 for the first
  // Where the teammates are now (map frame, as they report it) and whether this robot has
  // the right of way over them (e.g. the lower index). Call before update.
  void setTeammates(std::vector<Eigen::Vector2d> positions, bool priority);
  int teamStops() const { return team_.teamStops(); }
  int passageWaits() const { return team_.passageWaits(); }  // times it waited for a passage
  // The frontier goals teammates are driving to now (map frame): claimed while they drive
  // there (ExplorationGoals::claim), none after the robot imports the shared map
  // (continueAfterFix) until they are given again.
  void setTeammateGoals(const std::vector<Eigen::Vector2d>& goals);
  const std::vector<Eigen::Vector2d>& claimed() const { return goals_.claims(); }
  // The frontier goal this robot drives to, if it is exploring towards one.
  std::optional<Eigen::Vector2d> explorationGoal() const;
  int earlyReturns() const { return goals_.earlyReturns(); }
  MissionPhase phase() const { return phase_; }
  bool done() const { return phase_ == MissionPhase::kDone; }
  bool explorationComplete() const { return goals_.explorationComplete(); }
  int goalsReached() const { return goals_.goalsReached(); }
  int goalsFailed() const { return goals_.goalsFailed(); }
  int safetyStops() const { return safety_.stops(); }
  const std::string& lastEvent() const { return last_event_; }

 private:
  // One update's command, before the safety governor limits its speeding up: the policy.
  MotionCommand decide(double now, const Pose2& odometry, const OccupancyGrid& map,
                       const RadialMap* latest, bool bumped, std::optional<double> bump_bearing);
  // What a bump, or the end of backing off from one, makes the robot do now (nothing: none).
  std::optional<MotionCommand> afterBump(double now, const Pose2& odometry,
                                         const OccupancyGrid& map, bool bumped,
                                         std::optional<double> bump_bearing);
  // Waiting for a teammate in the passage or the way ahead, or planning around it (nothing:
  // the way is clear of them).
  std::optional<MotionCommand> giveWay(double now, const Pose2& odometry, const OccupancyGrid& map);
  // The phases' commands.
  MotionCommand lookAtHome(double now, const Pose2& odometry, const RadialMap* latest);
  // `fresh`: how many hits the obstacle memory took from `latest`.
  MotionCommand explore(double now, const Pose2& odometry, const OccupancyGrid& map,
                        const RadialMap* latest, size_t fresh);
  MotionCommand returnHome(double now, const Pose2& odometry, const OccupancyGrid& map,
                           const RadialMap* latest, size_t fresh);
  MotionCommand lookAgain(double now, const Pose2& odometry);
  // The way home near it is blocked: look at the home base from where the robot stands (a
  // fix will bring it home); `why` is the event.
  void lookFromHere(const Pose2& odometry, const std::string& why);

  void startRoute(std::vector<Waypoint> route);
  // Chooses the next frontier goal and drives there (or steps off, or goes home).
  void chooseGoal(double now, const Pose2& odometry, const OccupancyGrid& map);
  // Follows `path` to the exploration goal from `odometry`.
  void followToGoal(PlannedPath path, const Pose2& odometry);
  // Phase kReturn, on the way home from `odometry` (or waiting for one).
  void goHome(double now, const Pose2& odometry, const OccupancyGrid& map);
  // The maps to plan on from where the robot stands, with its teammates.
  PlanningMaps planningMaps(const OccupancyGrid& map) const;
  // The rest of the path being followed, from `pose` (or straight to the home target).
  std::vector<Eigen::Vector2d> wayAhead(const Pose2& pose) const;

  MissionConfig config_;
  SafetyGovernor safety_;
  ObstacleMemory memory_;
  ExplorationGoals goals_;
  Homing homing_;
  TeamTraffic team_;

  Pose2 home_;
  std::optional<Pose2> placed_home_;  // startFrom during the first look
  MissionPhase phase_ = MissionPhase::kLookAtHome;
  std::unique_ptr<RouteFollower> follower_;
  PlannedPath path_;                       // the path being followed (explore or return)
  std::optional<Waypoint> approach_look_;  // the look driven nearer to take (lookFrom)
  double start_time_ = -1.0;               // of the mission
  double sortie_start_ = -1.0;             // of the current sortie
  int sortie_ = 1;
  bool pose_jumped_ = false;
  double travelled_ = 0.0;         // m this sortie
  bool looked_from_here_ = false;  // the last look was taken where home was blocked
  Pose2 last_pose_;
  bool lost_ = false;
  std::string last_event_;
  MotionCommand last_command_;  // the last command decided
};

}  // namespace coopmap
