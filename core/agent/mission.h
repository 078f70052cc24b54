// A robot's mission (section 4 of the paper, autonomous): look at the home base, explore
// the frontiers of its own map with planned paths, keep itself safe, come home when the
// budget is spent or nothing reachable is left, and look at the home base again (the data
// the home-base protocol needs to correct the traverse). Robot-agnostic: it turns the pose
// estimate, the robot's map and its latest radial map into motion commands. Until the first
// look places the robot in the map frame (startFrom) it works in the odometry frame.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/agent/route_follower.h"
#include "core/mapping/occupancy_grid.h"
#include "core/perception/radial_map.h"
#include "core/planning/frontiers.h"
#include "core/planning/path_planner.h"
#include "core/planning/planning_map.h"

namespace coopmap {

struct MissionConfig {
  double budget_m = 60.0;   // m driven before going home
  double budget_s = 900.0;  // s of mission before going home
  // m driven before going home on the first sortie (0: budget_m). A short first sortie
  // brings the robot back while its odometry is still uncalibrated (its systematic heading
  // drift unknown) and near home; the fix calibrates the odometry for the longer ones.
  double first_budget_m = 0.0;
  // Home through unknown territory only if that way is at most this many times the straight
  // distance plus 2 m: a longer one (round a corridor loop) would drive the robot far through
  // places it has never seen while its odometry drifts. Else it drives to the free cell it can
  // reach nearest home and plans again from there.
  double max_home_detour = 2.0;
  // With no way home in the map, a robot farther than look_from_m from home first plans with
  // the least margin that still keeps its body off every blocked cell (sqrt(2) * resolution,
  // if planning.margin is more): a door drawn narrower than it is by the smear of its jambs
  // and the estimate's offset has room for the body without the margin (measured:
  // docs/experiments/2026-12-building-settings.md). With no way even so (a person in the
  // corridor, say), it stops and plans again after home_retry_s rather than drive straight at
  // home, which can take it into a mapped wall too close for the cameras to see.
  double home_retry_s = 2.0;  // s
  // After this many waits in a row with no way home in the map (0: never), it plans home on
  // its trail: the cells within its radius plus the least margin and a cell of where it has
  // driven this sortie count as free whatever the map drew there since. Its body passed
  // there; a stray cell in a door blocks the map, not the way, and a robot that waits on the
  // map alone can wait for good. The bumpers and teammates still block it, and what the
  // cameras have just seen off the trail; not what they see on it: a robot waiting in one
  // place sees the same things frame after frame, and a door's jambs seen obliquely put hits
  // in its opening for as long as it waits, closing the door again (measured:
  // docs/experiments/2026-12-building-sessions-25-34.md). The safety stop, on the latest
  // radial map, still stops it short of whatever stands on the trail.
  int trail_after_waits = 5;
  // When no frontier goal is left and some failed this sortie (or had no way to them): home to
  // share and try them again next sortie (the imported map is another, a teammate in the way
  // has moved on), rather than end exploration. A sortie that gets no farther than
  // min_sortie_m before that happens is idle; after kMaxIdleSorties idle sorties in a row
  // the frontiers are out of reach and exploration ends. Goals reached are remembered for
  // good: what the robot did not see from there it will not. Off: exploration ends there
  // (the paper's rooms; a building whose corridors a sortie cannot reach in one go wants it
  // on).
  bool retry_frontiers = false;
  static constexpr int kMaxIdleSorties = 2;
  double replan_period_s = 4.0;  // s between checks of the path against the growing map
  // m/s^2: the mission speeds up no faster than this (limitSpeedUp); slowing down and
  // stopping are left to the base's own limit. 0: as fast as the base does. Where the floor
  // grips less than the base's acceleration needs (polished tiles, mu 0.05, hold 0.49 m/s^2
  // against the B-14's 1 m/s^2) the wheels spin as the robot starts, and the encoders count
  // distance it never made.
  double max_linear_accel = 0.0;
  // m from the cameras: an obstacle this close ahead stops the robot. The stereo sees
  // nothing nearer than 0.26 m (32 disparities, 8 px m of focal length times baseline), and a
  // robot at 0.4 m/s moves 0.13 m between frames: 0.30 m leaves a narrow band. The agents
  // stop farther off and slow down as they near an obstacle (their safety_distance and
  // slow_distance, core/agent/agent_settings.h), which brings fewer contacts on the lab and
  // the building (measured: docs/experiments/2026-12-building-settings.md).
  double safety_distance = 0.30;
  double safety_half_angle = 0.5;  // rad: "ahead"
  // m: an obstacle ahead nearer than this slows the robot, in proportion down to
  // slow_fraction of its cruise at safety_distance (the cameras see 3 times a second and
  // nothing nearer than their stereo's least depth: at full speed a person walking towards
  // the robot can cross the whole band between that depth and safety_distance unseen).
  // 0: off.
  double slow_distance = 0.0;
  double slow_fraction = 0.35;
  // s: what the cameras saw in the last this many seconds (hits within recent_hits_range)
  // blocks the robot's planning, whatever its map holds there. Its map is mostly the shared
  // map, placed by corrected traverses that can be several cells off across a corridor
  // (measured: docs/experiments/2026-12-building-settings.md), and the cells it holds firmly
  // free take many hits to turn; a hit seen a moment ago is where it is relative to the
  // robot, to the drift of a few seconds. It matters where the cameras stop seeing what they
  // saw farther off: a textureless wall is seen only by where the floor ends, and the floor
  // only from 1.2 m. 0: off.
  double recent_hits_s = 0.0;
  // m: only hits this near the cameras are remembered, and only while this near the robot
  // (a local layer: the frontiers, and the goals, are chosen by the map alone).
  double recent_hits_range = 2.0;
  // Frames that must have seen a cell (within recent_hits_s): a stereo mismatch is seldom
  // seen twice in the same place, a wall is.
  int recent_hits_support = 2;
  double look_wait_s = 3.0;          // s facing the home base before the slow turn
  double look_turn_rate = 0.26;      // rad/s of the turns in place at home
  double goal_timeout_factor = 4.0;  // a goal not reached in this many times its path's
                                     // driving time is given up (blacklisted)
  double backoff_s = 1.5;            // s of backing off at 0.1 m/s after a bump
  double escape_radius = 0.6;        // m: a robot on a blocked cell steps to a free one this near
  double bump_radius = 0.1;          // m: what a bump shows is drawn as an obstacle disc this big
  // m: ... repeated across the robot's heading over this width (a bumper does not say how far
  // an edge goes on either side; a table edge the robot met head-on goes on).
  double bump_width = 0.5;
  // With the bearing of the touch from the base (RobotStatus::bump_bearing): back off away
  // from it (forwards from a touch behind) and draw what was touched at that bearing, spread
  // across it. Off, or without a bearing: straight back against the command, drawn ahead.
  bool bump_away = false;
  // Cells the robot has driven over count as free in its planning map unless the map holds
  // them occupied at least this firmly (log-odds in hundredths, OccupancyConfig).
  int firm_log_odds = 400;
  // m: the strip of driven-over cells kept free is this wide either side of the path (0: the
  // robot's radius). The whole footprint is free only where the robot stands now: a footprint
  // dragged along a wall it scraped (its estimate a few cm off) clears the wall's cells.
  double visited_radius = 0.0;
  // Sorties: with more than one, the budget is per sortie, and after each look at home the
  // mission waits (phase kAtHome) until the caller has localized it, corrected and shared
  // its traverse and imported the shared map (continueAfterFix), then goes again.
  int max_sorties = 1;
  // Teammates (setTeammates): one closer than team_distance ahead (within team_half_angle)
  // stops this robot; it waits, and after team_wait_s plans around the teammate (drawn into
  // its planning map as a disc of team_radius). The robot with priority waits only
  // team_wait_s / 4: one of two robots facing each other moves first.
  double team_distance = 1.0;     // m, centre to centre
  double team_half_angle = 1.05;  // rad
  double team_wait_s = 6.0;       // s
  double team_radius = 0.35;      // m: a teammate's body and a margin
  // m: a teammate ahead farther than this stops the robot only if the way ahead passes it
  // closer than its disc (once planned around, the robot drives on); nearer, always (what a
  // teammate reports is off by its drift until its next fix).
  double team_close = 0.6;
  // s: two robots converging from the sides do not see each other (their cameras look ahead).
  // The one without priority also stops, as for a teammate ahead, while at the speeds they
  // report (the teammate's over the last team_velocity_s) the teammate would come within
  // team_radius of its body in the next team_horizon_s.
  double team_horizon_s = 2.0;
  double team_velocity_s = 0.5;
  // Passages one robot at a time (a door): where the way ahead, within passage_lookahead,
  // runs between obstacles (occupied cells) less than passage_width apart, and a teammate is
  // within passage_radius of that place and nearer to it than this robot (or as near, and
  // this robot has no priority), the robot stops until the teammate is through and away, at
  // most passage_wait_s. A robot in the passage itself drives on. 0: off.
  double passage_width = 0.0;      // m
  double passage_lookahead = 1.5;  // m along the way
  double passage_radius = 1.2;     // m
  double passage_wait_s = 20.0;    // s
  // Bumped this many times on the way home within look_from_m of it, the robot looks at the
  // home base from where it is (the fix then takes it home).
  int max_return_bumps = 2;
  // Bumped this many times in one sortie, the robot stops for good (its wheels slipped: the
  // odometry is lost, and going on would only push into more things).
  int max_sortie_bumps = 6;
  double look_from_m = 2.0;
  // Coordination: teammates' frontier goals (setTeammateGoals) make frontiers near them worth
  // less (FrontierConfig::claim_radius). With sorties, when the best frontier left is claimed
  // this much (its factor below claimed_return_factor) after at least min_sortie_m driven, this
  // robot's part is explored: it goes home to share it rather than go over a teammate's part.
  // 0 turns the early return off.
  double claimed_return_factor = 0.5;
  double min_sortie_m = 3.0;
  FrontierConfig frontiers;
  // Bounded by sampling iterations, not by time: a run must not depend on how busy the
  // machine is (a query that runs out of time on a busy machine gives the same seed another
  // run). The time budget is only a backstop, far above what the iteration bound takes; the
  // bound is well above what the building's queries need (measured:
  // docs/experiments/2026-12-path-planning.md).
  PlannerConfig planner = [] {
    PlannerConfig p;
    p.max_iterations = 1'000'000;
    p.time_budget = 60.0;
    return p;
  }();
  PlanningMapConfig planning;
  RouteConfig route;
  void validate() const;  // throws std::invalid_argument naming the field
};

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
  void lookFrom(const Waypoint& look, double now);
  // In phase kAtStart: the look found no home base; turn again where it stands.
  void lookAgainAtStart(double now);

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
  int teamStops() const { return team_stops_; }
  int passageWaits() const { return passage_waits_; }  // times it waited for a passage
  // The frontier goals teammates are driving to now (map frame). They are remembered as
  // claimed until the robot imports the shared map (continueAfterFix).
  void setTeammateGoals(const std::vector<Eigen::Vector2d>& goals);
  const std::vector<Eigen::Vector2d>& claimed() const { return claims_; }
  // The frontier goal this robot drives to, if it is exploring towards one.
  std::optional<Eigen::Vector2d> explorationGoal() const;
  int earlyReturns() const { return early_returns_; }
  MissionPhase phase() const { return phase_; }
  bool done() const { return phase_ == MissionPhase::kDone; }
  bool explorationComplete() const { return exploration_complete_; }
  int goalsReached() const { return goals_reached_; }
  int goalsFailed() const { return goals_failed_; }
  int safetyStops() const { return safety_stops_; }
  const std::string& lastEvent() const { return last_event_; }

 private:
  void startRoute(std::vector<Waypoint> route, double now);
  // With `recent`, what the cameras just saw blocks too (recent_hits_s), but for what is so
  // near the robot that it could not start (that is the safety stop's and the bumpers').
  // `margin`: beyond the robot's radius, instead of planning.margin (< 0: planning.margin).
  // `trail`: the cells along this sortie's trail are free (trail_after_waits).
  // The least margin that keeps the body off every blocked cell: sqrt(2) cells.
  static double leastMargin(const MapLimits& lim) { return std::sqrt(2.0) * lim.resolution; }
  PlanningMap planningMap(const OccupancyGrid& map, bool allow_unknown, bool recent = true,
                          double margin = -1.0, bool trail = false) const;
  std::vector<Eigen::Vector2d> bumps_;  // where the bumpers touched something this sortie
  struct RecentHit {
    double t;
    int frame;          // counts the scans remembered
    Eigen::Vector2d p;  // map frame (the estimate's)
  };
  int recent_frames_ = 0;
  std::vector<RecentHit> recent_;  // hits of the last recent_hits_s, oldest first
  // Adds the scan's hits (dropping those too old); returns how many it added.
  size_t rememberHits(double now, const Pose2& odometry, const RadialMap& scan);
  // One of the last `fresh` recent hits lies within the planning clearance of the way ahead.
  bool freshHitOnWay(const Pose2& pose, size_t fresh) const;
  // `p` lies within `within` (m) of the polyline `way`.
  static bool nearWay(const std::vector<Eigen::Vector2d>& way, const Eigen::Vector2d& p,
                      double within);
  // The goal's frontier counts as seen: not a goal again (see retry_frontiers).
  void goalSeen();
  void markVisited(const OccupancyGrid& map, const Pose2& odometry);
  bool obstacleAhead(const RadialMap& scan) const;
  // The command with its forward speed capped by the nearest obstacle ahead (slow_distance).
  MotionCommand slowed(MotionCommand cmd) const;
  // update's command before max_linear_accel limits its speeding up.
  MotionCommand decide(double now, const Pose2& odometry, const OccupancyGrid& map,
                       const RadialMap* latest, bool bumped, std::optional<double> bump_bearing);
  double nearest_ahead_ = 1e9;  // m: the nearest hit ahead in the latest radial map
  void chooseGoal(double now, const Pose2& odometry, const OccupancyGrid& map);
  // The free cell nearest the robot within escape_radius, if any.
  std::optional<Eigen::Vector2d> nearestFreeCell(const PlanningMap& planning,
                                                 const Pose2& odometry) const;
  // The route along path_ to the goal, turning to face its frontier on arrival.
  std::vector<Waypoint> goalRoute(const Pose2& odometry) const;
  void goHome(double now, const Pose2& odometry, const OccupancyGrid& map);
  // The free cell of `from`'s region nearest `to`, if it is at least 0.5 m nearer than `from`.
  std::optional<Eigen::Vector2d> nearestReachable(const PlanningMap& planning, const Pose2& from,
                                                  const Eigen::Vector2d& to) const;

  Pose2 home_;
  Pose2 target_;                      // where "home" is this sortie (home_, or returnAgain's)
  std::optional<Pose2> placed_home_;  // startFrom during the first look
  MissionConfig config_;
  MissionPhase phase_ = MissionPhase::kLookAtHome;
  std::unique_ptr<RouteFollower> follower_;
  FrontierExplorer explorer_;
  PathPlanner planner_;
  PlannedPath path_;                 // the path being followed (explore or return)
  Eigen::Vector2d goal_{0, 0};       // its goal
  std::optional<double> goal_face_;  // the heading to turn to there, facing its frontier
  bool has_goal_ = false;
  double goal_deadline_ = 0.0;
  double backoff_until_ = -1.0;
  bool escaping_ = false;
  double last_check_ = 0.0;
  double start_time_ = -1.0;    // of the mission
  double sortie_start_ = -1.0;  // of the current sortie
  int sortie_ = 1;
  bool pose_jumped_ = false;
  bool plan_home_ = false;         // returnAgain: plan the way home at the next update
  bool plan_home_at_end_ = false;  // the route ends short of home: plan again there
  std::string complete_reason_;    // why exploration was found complete
  int sortie_goals_ = 0;           // goals reached this sortie
  int idle_sorties_ = 0;  // sorties in a row ended for unreachable frontiers, short of min_sortie_m
  int return_bumps_ = 0;
  int sortie_bumps_ = 0;
  std::optional<Waypoint> approach_look_;  // the look driven nearer to take (lookFrom)
  std::vector<Eigen::Vector2d> teammates_;
  std::vector<Eigen::Vector2d> claims_;  // teammates' goals since the last import
  int early_returns_ = 0;
  bool priority_ = false;
  double team_wait_until_ = -1.0;  // waiting for a teammate ahead until then
  int team_stops_ = 0;
  bool teammateAhead(const Pose2& pose) const;
  // A teammate ahead, or (without priority) one converging on this robot's way.
  bool teammateInTheWay(const Pose2& pose) const;
  // Where the teammates were team_velocity_s ago, and their velocities since (map frame).
  void trackTeammates(double now);
  std::vector<Eigen::Vector2d> teammates_before_;
  std::vector<Eigen::Vector2d> teammate_velocities_;
  double teammates_before_at_ = -1.0;
  // The rest of the path being followed, from `pose` (or straight to the target).
  std::vector<Eigen::Vector2d> wayAhead(const Pose2& pose) const;
  // The first place within passage_lookahead along the way where it runs through a passage
  // (see passage_width), if any; `here` says whether the robot stands in it now.
  std::optional<Eigen::Vector2d> passageAhead(const Pose2& pose, const OccupancyGrid& map,
                                              bool* here) const;
  // A teammate holds the passage ahead: wait for it (passage_width).
  bool passageHeld(const Pose2& pose, const OccupancyGrid& map) const;
  double passage_wait_since_ = -1.0;  // waiting for a passage since then
  double home_retry_at_ = -1.0;       // no way home: plan again then
  double home_margin_ = -1.0;         // the way home's margin, when not planning.margin (else < 0)
  int home_waits_ = 0;                // waits in a row with no way home
  bool home_on_trail_ = false;        // the way home is planned on the trail
  double passage_next_ = -1.0;        // after a wait that timed out: no waiting until then
  int passage_waits_ = 0;
  double travelled_ = 0.0;
  Pose2 last_pose_;
  bool exploration_complete_ = false;
  int goals_reached_ = 0, goals_failed_ = 0, safety_stops_ = 0;
  bool lost_ = false;
  std::string last_event_;
  MotionCommand last_command_;
  double sent_linear_ = 0.0;     // m/s: the linear speed of the last command update returned
  double sent_at_ = -1.0;        // s: when (negative: none yet)
  GridU8 visited_;               // cells the robot's body has covered: free, seen or not
  GridU8 trail_;                 // this sortie's: see trail_after_waits
  double backoff_speed_ = -0.1;  // m/s while backing off from a bump
};

}  // namespace coopmap
