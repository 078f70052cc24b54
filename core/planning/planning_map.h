// The conservative map a robot plans on: blocked cells (occupied, and unknown unless
// allowed) inflated by the robot's radius plus a safety margin through a distance map.
#pragma once

#include <cstdint>
#include <optional>

#include <Eigen/Core>

#include "core/mapping/grid.h"
#include "core/mapping/occupancy_grid.h"

namespace coopmap {

struct RobotDescription;

struct PlanningMapConfig {
  double robot_radius = 0.178;  // m; RobotDescription::body_radius of the B-14
  // m beyond the radius. Clearances are measured between cell centres, so a robot centred
  // anywhere in a free cell keeps at least radius + margin - sqrt(2) * resolution from
  // every blocked cell's square: a margin of sqrt(2) * resolution makes that a guarantee.
  double margin = 0.05;
  bool allow_unknown = false;  // true: unknown cells count as free (driving into frontiers)

  // The config for a robot: its body radius, the default margin.
  static PlanningMapConfig forRobot(const RobotDescription& robot);
  void validate() const;  // throws std::invalid_argument naming the field and the value
};

// Built once per map version (cheap: see bench/planner_bench.cpp), then read-only.
// Outside the map counts as blocked: the robot's body stays inside the map's limits.
class PlanningMap {
 public:
  // From a mapper's grid: CellState per cell by its thresholds and seen layer.
  PlanningMap(const OccupancyGrid& grid, const PlanningMapConfig& config);
  // From a grid of CellState values (literal maps, ground truth, maps read from files).
  PlanningMap(const Grid<CellState>& states, const PlanningMapConfig& config);

  const MapLimits& limits() const { return limits_; }
  const PlanningMapConfig& config() const { return config_; }

  // Occupied, or unknown when unknown is not allowed. Precondition: inside the map.
  bool blocked(int ix, int iy) const { return blocked_.at(ix, iy) != 0; }
  // m from the cell's centre to the nearest blocked cell's centre (or to the ring of cells
  // just outside the map); 0 on blocked cells. Precondition: inside the map.
  double clearance(int ix, int iy) const { return clearance_.at(ix, iy); }
  // The robot may stand in the cell: clearance > robot_radius + margin. False outside.
  bool free(int ix, int iy) const { return limits_.contains(ix, iy) && free_.at(ix, iy) != 0; }
  // free() of the cell holding the world point (m).
  bool freeAt(const Eigen::Vector2d& p) const {
    return free(limits_.cellX(p.x()), limits_.cellY(p.y()));
  }
  // Every cell the segment a -> b (m) passes through, corners included, is free. Walked both
  // ways, so that it is symmetric: an end exactly on a cell corner is rounded into one cell,
  // and the walk starting there checks the corner's other cells, the walk ending there not.
  bool segmentFree(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const {
    return !firstBlockedOnSegment(a, b).has_value() && !firstBlockedOnSegment(b, a).has_value();
  }
  // Fraction t in [0, 1] of a -> b where it first enters a cell that is not free (0 when a's
  // own cell is not); nullopt when the whole segment is free.
  std::optional<double> firstBlockedOnSegment(const Eigen::Vector2d& a,
                                              const Eigen::Vector2d& b) const;
  // Label of the 4-connected region of free cells holding the cell; 0 when not free. Two
  // free cells are joined by a collision-free polyline iff their labels are equal.
  int region(int ix, int iy) const { return free(ix, iy) ? region_.at(ix, iy) : 0; }
  // Both points lie in free cells of the same region (m).
  bool connected(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;

  const GridU8& blockedGrid() const { return blocked_; }  // 1 = blocked
  const GridU8& freeGrid() const { return free_; }        // 1 = free for the robot
  const Grid<float>& clearanceGrid() const { return clearance_; }

 private:
  void build();

  PlanningMapConfig config_;
  MapLimits limits_;
  GridU8 blocked_;
  Grid<float> clearance_;
  GridU8 free_;
  Grid<int32_t> region_;
};

}  // namespace coopmap
