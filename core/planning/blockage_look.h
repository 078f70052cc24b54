// What closes the way to a frontier out of the robot's reach, and where to look at it from.
// A frontier without a reachable goal, or looked at from its goal and still there, may lie
// beyond cells the planning map holds blocked: a wall, or what the map holds and the building
// does not (a person who stood in a doorway for a while, a door's jamb smeared into its
// opening by oblique views). Stereo maps what it is shown; a second look at the blockage
// from in front, long enough for the grid's evidence to turn, keeps what stands and clears
// what does not. The way to the frontier is the cheapest one through the known cells,
// blocked ones passable at a price (never-observed cells not): where it leaves the robot's
// free region is the blockage.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "core/mapping/occupancy_grid.h"
#include "core/planning/frontiers.h"
#include "core/planning/planning_map.h"

namespace coopmap {

struct BlockageLook {
  Eigen::Vector2d from{0.0, 0.0};      // m: a free cell of the robot's region to look from
  Eigen::Vector2d at{0.0, 0.0};        // m: the blockage's middle, on the way to the frontier
  double heading = 0.0;                // rad: from `from` towards `at`
  Eigen::Vector2d frontier{0.0, 0.0};  // m: the centroid of the frontier it closes the way to
};

// m from the blockage the look is taken from: near enough that the stereo sees the blockage
// and what is beyond it sharply, far enough that the cameras' view spans a doorway and its
// jambs (and nearer than the stereo's range to the walls beyond).
inline constexpr double kBlockageLookDistance = 1.2;

// The look at what closes the way to the frontier of most gain among `frontiers` (as
// findFrontiers gives them for `grid` and `planning` from `robot`) that lie outside the robot's
// free region, skipping blockages within `skip_radius` (m) of one in `looked`. Nothing when the
// robot stands on no free cell, or every frontier is in its region, beyond reach through known
// cells, or behind a blockage looked at.
std::optional<BlockageLook> findBlockageLook(const OccupancyGrid& grid, const PlanningMap& planning,
                                             const Eigen::Vector2d& robot,
                                             const std::vector<Frontier>& frontiers,
                                             const std::vector<Eigen::Vector2d>& looked,
                                             double skip_radius);

}  // namespace coopmap
