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
  // Coordination (Burgard et al., "Coordinated multi-robot exploration", 2005): a frontier
  // whose goal lies within claim_radius of a point a teammate has claimed (its goals) is
  // worth less by the chance that the teammate sees it: utility * distance / claim_radius.
  double claim_radius = 2.5;  // m; 0 turns coordination off
  void validate() const;      // throws std::invalid_argument naming the field
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

// kBlocked: the robot stands on a cell the planning map holds blocked, so nothing can be
// planned from where it is (which says nothing about what is left to explore).
enum class ExploreStatus { kGoal, kDone, kBlocked };

struct ExploreStep {
  ExploreStatus status = ExploreStatus::kDone;
  Frontier frontier;          // the chosen one
  PlanResult plan;            // the path to its goal
  int frontiers = 0;          // found this time (with or without a reachable goal)
  double claim_factor = 1.0;  // of the chosen one: 1 unclaimed, near 0 a teammate's goal
  std::string reason;         // why done
};

// Chooses where to explore next; remembers failed goals.
class FrontierExplorer {
 public:
  FrontierExplorer(const FrontierConfig& frontiers, const PlannerConfig& planner);

  // The best frontier to go to from `robot` on `grid` (planning map built with the
  // robot's radius), with its plan; kDone when no reachable frontier is left. `claimed`:
  // where teammates explore (map frame), see FrontierConfig::claim_radius.
  ExploreStep next(const OccupancyGrid& grid, const PlanningMap& planning, const Pose2& robot,
                   const std::vector<Eigen::Vector2d>& claimed = {});
  // The factor by which `claimed` lowers the utility of a frontier whose goal is `goal`.
  double claimFactor(const Eigen::Vector2d& goal,
                     const std::vector<Eigen::Vector2d>& claimed) const;
  // The robot could not reach this goal: never choose it (or a goal near it) again.
  void blacklist(const Eigen::Vector2d& goal) { blacklist_.push_back(goal); }
  // Forgets the failed goals (the map, or the frame it is in, changed).
  void clearBlacklist() { blacklist_.clear(); }
  const std::vector<Eigen::Vector2d>& blacklisted() const { return blacklist_; }

 private:
  bool blacklisted(const Eigen::Vector2d& goal) const;
  FrontierConfig config_;
  PathPlanner planner_;
  std::vector<Eigen::Vector2d> blacklist_;
};

}  // namespace coopmap
