// Path planning with OMPL on a PlanningMap: a collision-free polyline from a start pose to a
// goal point, simplified, as the paper's robots drive it: turns in place joined by straight
// segments.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/pose2.h"
#include "core/planning/planning_map.h"
#include "core/robot/robot_interface.h"

namespace coopmap {

// OMPL 1.5.2's LazyPRM(*) leaks states on every solve (ompl/ompl#833, fixed after 1.5), so
// it is not offered.
enum class PlannerType : uint8_t { kRRTConnect, kPRMstar, kRRTstar };

// "rrt-connect", "prm-star", "rrt-star".
const char* toString(PlannerType type);
// The type named by toString(); throws std::invalid_argument listing the names otherwise.
PlannerType parsePlannerType(const std::string& name);

struct PlannerConfig {
  PlannerType planner = PlannerType::kRRTConnect;
  // s of planning (simplification is extra). RRTConnect stops at its first solution; the
  // optimizing planners (PRM*, RRT*) use the whole budget.
  double time_budget = 1.0;
  // Sampling iterations (planner termination checks) allowed; 0 = no limit. With a limit
  // that is reached before the time budget, RRT* is deterministic as well.
  uint64_t max_iterations = 0;
  uint32_t seed = 1;  // same seed, same map, same query: same path (see PathPlanner)
  // m; longest edge a tree grows in one step. 0 = OMPL's default (a fifth of the map's
  // diagonal).
  double range = 0.0;
  bool simplify = true;     // shortcutting and vertex reduction (OMPL's PathSimplifier)
  int simplify_rounds = 4;  // rounds of reduceVertices + shortcutPath
  // m beyond the robot's radius the path keeps from blocked cells where the map leaves room
  // (keepClear, after simplification; 0: off). The map's margin is what the robot must keep;
  // this is what it keeps where it can: in the open, away from walls; in a door only as
  // wide as the robot needs, through its middle.
  double preferred_margin = 0.0;

  void validate() const;  // throws std::invalid_argument naming the field and the value
};

// A plan's outcome, in the manner of OMPL's base::PlannerStatus.
enum class PlanStatus : uint8_t {
  kSolved,        // a collision-free path
  kStartInvalid,  // the start is outside the map or not free for the robot
  kGoalInvalid,   // the goal is outside the map or not free for the robot
  kNoPath,        // start and goal lie in different free regions: no path exists
  kTimeout,       // a path exists but the planner found none within its budget
};
const char* toString(PlanStatus status);

// A path in the map's frame (m), driven as turns in place and straight segments.
struct PlannedPath {
  // Start first, goal last (two points even when they coincide); no other repeats.
  std::vector<Eigen::Vector2d> waypoints;
  // turn(angle to the next waypoint), straight(distance), ... and a final turn to the goal
  // heading when one was asked for. Zero turns are left out.
  std::vector<MotionCommand> commands;

  double length() const;  // m along the waypoints
};

struct PlanResult {
  PlanStatus status = PlanStatus::kTimeout;
  std::string reason;        // for people: why it failed, or what was found
  PlannedPath path;          // empty unless solved
  size_t raw_waypoints = 0;  // vertices of the planner's path before simplification
  double raw_length = 0.0;   // m, the same path's length

  bool solved() const { return status == PlanStatus::kSolved; }
};

// The drive for a polyline: from `start_heading` (rad) turn to face each next waypoint,
// then go straight to it; finally turn to `goal_heading` if given. Consecutive points
// closer than 1e-9 m are merged.
std::vector<MotionCommand> turnsAndStraights(const std::vector<Eigen::Vector2d>& waypoints,
                                             double start_heading,
                                             std::optional<double> goal_heading);

// Index of the first segment of the path (waypoints[i] -> waypoints[i + 1]) that passes
// through a cell not free on `map`; nullopt when the whole path is still free.
std::optional<size_t> firstBlockedSegment(const std::vector<Eigen::Vector2d>& waypoints,
                                          const PlanningMap& map);
// No segment of the path passes through a cell that is not free on `map` (e.g. after the
// map changed under it). An empty path is not valid.
bool pathStillValid(const PlannedPath& path, const PlanningMap& map);

// Plans with OMPL over the map's limits (a 2D real-vector space: the robot is a disc that
// turns in place, so its heading does not matter for collisions). States are valid in free
// cells of the planning map; motions are checked exactly against every cell a segment
// crosses (PlanningMap::firstBlockedOnSegment), not by sampling.
//
// Determinism: OMPL's global seed (ompl::RNG::setSeed) only seeds the generator that gives
// every new RNG its seed, and it can be set only once per process, before the first RNG
// exists; it cannot make the second plan of a process repeat the first. So the RNGs that
// shape the path, the planner's state sampler and the path simplifier's, are seeded per
// plan with RNG::setLocalSeed from PlannerConfig::seed: the same seed, map and query give
// the same path whatever was planned before, for planners that stop at their first
// solution (RRTConnect) or at max_iterations (RRT*). PRM* grows its roadmap while another
// thread checks for solutions, so its paths depend on timing. The global seed is
// set once, to a fixed value, on first use, so the RNGs we cannot reach (nearest-neighbour
// structures) also repeat from run to run. OMPL's console messages below warnings are
// switched off on first use.
class PathPlanner {
 public:
  explicit PathPlanner(const PlannerConfig& config = {});

  // A path from the start pose to the goal point (map frame, m, rad), ending with a turn to
  // `goal_heading` if given. Never a path through a cell that is not free on `map`.
  PlanResult plan(const PlanningMap& map, const Pose2& start, const Eigen::Vector2d& goal,
                  std::optional<double> goal_heading = std::nullopt) const;

  // For a robot at `current` following `path`, heading for path.waypoints[next_waypoint]:
  // when the rest of the path (current -> waypoints[next_waypoint] -> ... -> goal) is still
  // free on `map`, returns it unchanged (replanned = false); otherwise plans anew from
  // `current` to the same goal and heading. Precondition: next_waypoint < waypoints.size().
  struct Replan {
    PlanResult result;
    bool replanned = false;
  };
  Replan replanIfBlocked(const PlanningMap& map, const PlannedPath& path, const Pose2& current,
                         size_t next_waypoint,
                         std::optional<double> goal_heading = std::nullopt) const;

  const PlannerConfig& config() const { return config_; }

 private:
  // keepClear with the preferred margin, when there is one.
  std::vector<Eigen::Vector2d> keepClearOf(const PlanningMap& map,
                                           std::vector<Eigen::Vector2d> w) const;

  PlannerConfig config_;
};

}  // namespace coopmap
