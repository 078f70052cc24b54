// The mission's goal selection (core/agent/mission.h): which frontier to explore next (the
// frontier explorer, with the goals teammates have claimed), the goal's deadline, paths to it
// around what blocks the way, and what becomes of a goal: reached (its frontier seen),
// given up (blacklisted for the sortie), or dropped for now. It decides too when exploring
// should stop for a sortie or for good: no frontier within reach, or the frontiers left are
// teammates' (claimed_return_factor).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/agent/mission_config.h"
#include "core/agent/obstacle_memory.h"
#include "core/planning/blockage_look.h"
#include "core/planning/frontiers.h"
#include "core/planning/path_planner.h"

namespace coopmap {

// What to do after choosing a goal (ExplorationGoals::choose).
struct GoalChoice {
  enum class Kind {
    kStepOff,  // drive `route` off the blocked cell the robot stands on; its path is unchanged
    kGoHome,   // explore no more this sortie
    kGoal,     // drive `route` along `path` to the new goal
  };
  Kind kind = Kind::kGoHome;
  std::vector<Waypoint> route;
  PlannedPath path;
  std::string event;  // what happened, for MissionAgent::lastEvent
};

// The outcome of checking the path to the goal against the grown map (ExplorationGoals::recheck).
struct GoalCheck {
  enum class Kind {
    kClear,        // the rest of the path is still free
    kReplanned,    // blocked: `path` is a new one to the goal
    kTakenAsSeen,  // the goal is blocked by what the cameras have just seen: its frontier is seen
    kGivenUp,      // blocked, and no new path: the goal is given up
  };
  Kind kind = Kind::kClear;
  PlannedPath path;
  std::string event;  // what happened, for MissionAgent::lastEvent
};

class ExplorationGoals {
 public:
  explicit ExplorationGoals(const MissionConfig& config);

  // The next goal for the robot at `odometry` at `now` (s), on `maps`, `travelled` m into
  // its sortie; or why none (then a step off a blocked cell first, or home).
  GoalChoice choose(double now, const Pose2& odometry, const PlanningMaps& maps, double travelled);
  // The route along `path` to the goal, turning to face its frontier on arrival.
  std::vector<Waypoint> route(const PlannedPath& path, const Pose2& odometry) const;
  // A path from `odometry` to the goal on the planning map (what the cameras have just seen
  // included), if there is one.
  std::optional<PlannedPath> pathAround(const PlanningMaps& maps, const Pose2& odometry);
  // The path is due for a check against the grown map at `now` (s): `seen_on_way` (something
  // just seen on the way ahead) or replan_period_s since the last check. Starts the period.
  bool checkDue(double now, bool seen_on_way);
  // Checks `path`, followed towards its waypoint `next`, against `maps`; counts and
  // blacklists a goal given up, marks a goal taken as seen.
  GoalCheck recheck(const PlanningMaps& maps, const PlannedPath& path, const Pose2& odometry,
                    size_t next);

  bool hasGoal() const { return has_goal_; }
  // The path to the goal is the map's, cut by what the cameras have just seen (no way round
  // it): the robot stops short of what was seen ahead while it is remembered.
  bool byMap() const { return has_goal_ && by_map_; }
  const Eigen::Vector2d& goal() const { return goal_; }
  bool overdue(double now) const { return has_goal_ && now > goal_deadline_; }
  // The robot arrived (with or without a goal): counted; the goal's frontier is seen.
  void reached();
  // The goal failed (counted): not chosen again this sortie.
  void giveUp();
  // No goal for now: the way is only blocked for now, or the robot does something else.
  void drop() {
    has_goal_ = false;
    looking_ = false;
    by_map_ = false;
  }

  // Teammates drive to these frontier goals now (map frame): claimed while they do. A goal a
  // teammate has reached it looked from (the frontiers left there it will not see), and one
  // it turned from is no one's: the claims are the goals given last.
  void claim(const std::vector<Eigen::Vector2d>& goals) { claims_ = goals; }
  const std::vector<Eigen::Vector2d>& claims() const { return claims_; }
  // A new sortie after the import of the shared map: the claims are in the map now, and the
  // goals failed in the old frame, on the old map; no goal.
  void startSortie();

  bool explorationComplete() const { return exploration_complete_; }
  const std::string& completeReason() const { return complete_reason_; }
  int goalsReached() const { return goals_reached_; }
  int goalsFailed() const { return goals_failed_; }
  int earlyReturns() const { return early_returns_; }

 private:
  // The goal's frontier counts as seen: not a goal again (see retry_frontiers).
  void seen();
  // When no frontier has a goal the robot can reach: a look at what closes the way to one
  // (findBlockageLook), each blockage looked at once; nothing when there is none to look at.
  std::optional<GoalChoice> lookAtBlockage(double now, const Pose2& odometry,
                                           const PlanningMaps& maps, const PlanningMap& planning,
                                           const ExploreStep& step);
  // The rest of `path` from `next` on `map` (without what the cameras have just seen), or a
  // new path to its end when that is blocked; nothing when `map` has no way either.
  std::optional<PlannedPath> pathByMap(const PlanningMap& map, const PlannedPath& path,
                                       const Pose2& odometry, size_t next) const;

  MissionConfig config_;
  FrontierExplorer explorer_;
  PathPlanner planner_;
  Eigen::Vector2d goal_{0, 0};
  std::optional<double> goal_face_;  // the heading to turn to there, facing its frontier
  double goal_wait_ = 0.0;           // s to stand there, facing it
  bool looking_ = false;             // the goal is a place to look at a blockage from
  bool by_map_ = false;              // see byMap()
  // Blockages looked at (map frame), for good; while looking_, the last is the one looked at.
  std::vector<Eigen::Vector2d> looked_;
  bool has_goal_ = false;
  double goal_deadline_ = 0.0;           // s: given up if not reached by then
  double last_check_ = 0.0;              // s: the path's last check against the map
  bool escaping_ = false;                // stepping off a blocked cell
  std::vector<Eigen::Vector2d> claims_;  // teammates' goals now
  int idle_sorties_ = 0;  // sorties in a row ended for unreachable frontiers, short of min_sortie_m
  int early_returns_ = 0;
  bool exploration_complete_ = false;
  std::string complete_reason_;  // why exploration was found complete
  int goals_reached_ = 0, goals_failed_ = 0;
};

}  // namespace coopmap
