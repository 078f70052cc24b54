// Frontier exploration (Yamauchi 1997), on the map's seen layer: frontiers are observed free
// cells next to never-observed ones, grouped; each gets a goal the robot can stand on and
// reach, an information gain (unknown cells near it) and a path cost (the planner's path
// length); the explorer picks the best gain per cost, and failed goals are blacklisted, not
// fatal. Exploration is over when no reachable frontier is left.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/pose2.h"
#include "core/mapping/occupancy_grid.h"
#include "core/planning/path_planner.h"
#include "core/planning/planning_map.h"

namespace coopmap {

struct FrontierConfig {
  int min_cells = 4;                // smaller groups of frontier cells are noise
  double gain_radius = 1.5;         // m: unknown cells this close to a frontier are its gain
  double goal_search_radius = 1.5;  // m: the goal is a free cell this close to the frontier
  double cost_weight = 1.0;         // utility = gain cells / (1 + cost_weight * path metres)
  double blacklist_radius = 0.5;    // m: goals this close to a failed one are skipped
  int max_plans = 5;                // frontiers (best by straight-line utility) planned to
  void validate() const;            // throws std::invalid_argument naming the field
};

struct Frontier {
  std::vector<Eigen::Vector2d> cells;  // centres of its cells (m)
  Eigen::Vector2d centroid{0.0, 0.0};  // m
  bool has_goal = false;               // a reachable cell the robot can stand on, near it:
  Eigen::Vector2d goal{0.0, 0.0};      // m (valid when has_goal)
  int gain = 0;                        // unknown cells within gain_radius of the centroid
};

// Frontier cells: observed free cells with a 4-neighbour never observed; grouped
// 8-connected; groups smaller than min_cells dropped. Goals are looked for in `planning`'s
// free cells connected to `robot` (m); frontiers without one have has_goal false.
std::vector<Frontier> findFrontiers(const OccupancyGrid& grid, const PlanningMap& planning,
                                    const Eigen::Vector2d& robot, const FrontierConfig& config);

enum class ExploreStatus { kGoal, kDone };

struct ExploreStep {
  ExploreStatus status = ExploreStatus::kDone;
  Frontier frontier;   // the chosen one
  PlanResult plan;     // the path to its goal
  int frontiers = 0;   // found this time (with or without a reachable goal)
  std::string reason;  // why done
};

// Chooses where to explore next; remembers failed goals.
class FrontierExplorer {
 public:
  FrontierExplorer(const FrontierConfig& frontiers, const PlannerConfig& planner);

  // The best frontier to go to from `robot` on `grid` (planning map built with the
  // robot's radius), with its plan; kDone when no reachable frontier is left.
  ExploreStep next(const OccupancyGrid& grid, const PlanningMap& planning, const Pose2& robot);
  // The robot could not reach this goal: never choose it (or a goal near it) again.
  void blacklist(const Eigen::Vector2d& goal) { blacklist_.push_back(goal); }
  const std::vector<Eigen::Vector2d>& blacklisted() const { return blacklist_; }

 private:
  bool blacklisted(const Eigen::Vector2d& goal) const;
  FrontierConfig config_;
  PathPlanner planner_;
  std::vector<Eigen::Vector2d> blacklist_;
};

}  // namespace coopmap
