// The mission's homing (core/agent/mission.h): the way home at the end of a sortie. Home on
// the planning map; through unknown territory if that way is short (max_home_detour); else
// as near home as the known free space goes, planning again there; else with the least
// margin; after trail_after_waits waits, on the trail driven out; else wait and plan again
// after home_retry_s. It says when the way home is due to be planned again, which map the
// way home was planned on (to check it against what the cameras see), and when bumps near
// home say the way is blocked (max_return_bumps).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/agent/mission_config.h"
#include "core/agent/obstacle_memory.h"
#include "core/planning/path_planner.h"

namespace coopmap {

// The way home from where the robot stands (Homing::plan).
struct HomeWay {
  PlannedPath path;  // the path followed home (empty: straight home, or no way)
  // The route to drive; none: no way home in the map now, wait and plan again.
  std::optional<std::vector<Waypoint>> route;
  std::string event;  // what happened, for MissionAgent::lastEvent (empty: nothing to say)
};

class Homing {
 public:
  // `home`: where home is (map frame).
  Homing(const MissionConfig& config, const Pose2& home);

  // Where "home" is this sortie (map frame).
  const Pose2& target() const { return target_; }
  void setTarget(const Pose2& home) { target_ = home; }
  // A new sortie, home at `home`: no bumps on the way home, no waits for a way.
  void startSortie(const Pose2& home);
  // Home is at `home` after all (a fix showed the estimate off): plan the way there at the
  // next update, the bumps on the way home forgotten.
  void returnTo(const Pose2& home);

  // The way home from `odometry` at `now` (s) on `maps`.
  HomeWay plan(double now, const Pose2& odometry, const PlanningMaps& maps);
  // The way home is due to be planned at `now` (s): asked for (returnTo), or the wait for a
  // way is over.
  bool planDue(double now);
  // A route was started: any wait for a way home is over.
  void routeStarted() { retry_at_ = -1.0; }
  // The way planned ends short of home (as near as the map went): plan again there.
  bool endsShort() const { return ends_short_; }
  // The planning map the way home was planned on (its margin, the trail).
  PlanningMapOptions wayMap() const { return {.margin = margin_, .trail = on_trail_}; }
  // A bump on the way home, the robot at `odometry`: true when it is the max_return_bumps-th
  // within look_from_m of home (the way is blocked: look at the home base from there).
  bool blockedNearHome(const Pose2& odometry);
  // Within look_from_m of home: near enough to look at the home base from there.
  bool nearHome(const Pose2& odometry) const;

 private:
  MissionConfig config_;
  PathPlanner planner_;
  Pose2 target_;
  bool plan_due_ = false;    // returnTo: plan the way home at the next update
  bool ends_short_ = false;  // the route ends short of home: plan again there
  double retry_at_ = -1.0;   // s: no way home, plan again then (negative: not waiting)
  double margin_ = -1.0;     // the way home's margin, when not planning.margin (else < 0)
  int waits_ = 0;            // waits in a row with no way home
  bool on_trail_ = false;    // the way home is planned on the trail
  int bumps_ = 0;            // bumps on the way home
};

}  // namespace coopmap
