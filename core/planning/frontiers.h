// Frontier exploration (Yamauchi 1997): frontiers are free cells next to cells not known
// (never observed, or observed too little to tell, on the far side of long rays), grouped; each
// gets a goal the robot can stand on and reach, an information gain (unknown cells near it) and a
// path cost (the planner's path length); the explorer picks the best gain per cost, and failed
// goals are blacklisted, not fatal. Exploration is over when no reachable frontier is left.
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
  // m: cells observed but uncertain, this far from any occupied cell and joined to never-
  // observed ones, count as unknown for frontiers (the fringe long stereo rays leave); 0:
  // only never-observed cells do.
  double fringe_clearance = 0.0;
  // m: uncertain cells within fringe_clearance of obstacles count as unknown all the same
  // where they lie in an opening: between two obstacles on opposite sides (along a grid axis
  // or a diagonal) at most this far apart and at least doorway_min_width. A door seen only
  // obliquely leaves its opening uncertain and its jambs smeared: with fringe_clearance alone
  // no frontier leads through it, and whatever lies beyond goes unexplored (measured on the
  // building's lab back door: docs/experiments/2026-12-building-settings.md). 0: off.
  double doorway_width = 0.0;
  double doorway_min_width = 0.25;  // m: narrower gaps are no way through
  void validate() const;            // throws std::invalid_argument naming the field
};

struct Frontier {
  std::vector<Eigen::Vector2d> cells;  // centres of its cells (m)
  Eigen::Vector2d centroid{0.0, 0.0};  // m
  bool has_goal = false;               // a reachable cell the robot can stand on, near it:
  Eigen::Vector2d goal{0.0, 0.0};      // m (valid when has_goal)
  int gain = 0;                        // never-observed cells within gain_radius of the centroid
};

// Frontier cells: free cells with a 4-neighbour not known (never observed, or observed but
// uncertain, away from obstacles or in an opening between two, and joined to never-observed
// cells: fringe_clearance, doorway_width); grouped
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
  int failed_left = 0;        // when done: frontiers whose goals failed or that have none
  // When done: the frontiers without a reachable goal, and those looked at from their goals
  // and still there (what closes the way to them may be a blockage to look at).
  std::vector<Frontier> out_of_reach;
};

// Chooses where to explore next; remembers failed goals.
class FrontierExplorer {
 public:
  FrontierExplorer(const FrontierConfig& frontiers, const PlannerConfig& planner);

  // The best frontier to go to from `robot` on `grid` (planning map built with the
  // robot's radius), with its plan; kDone when no reachable frontier is left. `claimed`:
  // where teammates explore (map frame), see FrontierConfig::claim_radius. Frontiers on the
  // fringe of uncertain cells (fringe_clearance) are looked at only when no frontier on
  // never-observed cells has a goal: near obstacles they draw the robot into bumps.
  ExploreStep next(const OccupancyGrid& grid, const PlanningMap& planning, const Pose2& robot,
                   const std::vector<Eigen::Vector2d>& claimed = {});
  // The factor by which `claimed` lowers the utility of a frontier whose goal is `goal`.
  double claimFactor(const Eigen::Vector2d& goal,
                     const std::vector<Eigen::Vector2d>& claimed) const;
  // The robot could not reach this goal: never choose it (or a goal near it) again.
  void blacklist(const Eigen::Vector2d& goal) { blacklist_.push_back(goal); }
  // The robot reached this goal and looked from there: what it did not see then it will
  // not see from there again. Kept across clearBlacklist (never chosen again).
  void markReached(const Eigen::Vector2d& goal) { reached_.push_back(goal); }
  // Forgets the failed goals (the map, or the frame it is in, changed); not the reached ones.
  void clearBlacklist() { blacklist_.clear(); }
  const std::vector<Eigen::Vector2d>& blacklisted() const { return blacklist_; }

 private:
  bool blacklisted(const Eigen::Vector2d& goal) const;
  ExploreStep nextWith(const FrontierConfig& config, const OccupancyGrid& grid,
                       const PlanningMap& planning, const Pose2& robot,
                       const std::vector<Eigen::Vector2d>& claimed);
  static bool near(const std::vector<Eigen::Vector2d>& places, const Eigen::Vector2d& goal,
                   double radius);
  FrontierConfig config_;
  PathPlanner planner_;
  std::vector<Eigen::Vector2d> blacklist_;
  std::vector<Eigen::Vector2d> reached_;
  bool reached(const Eigen::Vector2d& goal) const;
};

}  // namespace coopmap
