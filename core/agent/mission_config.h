// The mission's settings (core/agent/mission.h): one plain struct the mission and each of its
// parts (the safety governor, the obstacle memory, goal selection, homing, team traffic) read.
#pragma once

#include "core/agent/route_follower.h"
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

}  // namespace coopmap
