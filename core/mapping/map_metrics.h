// Map quality against the true occupancy of the world (same MapLimits as the map).
#pragma once

#include <array>

#include "core/mapping/grid.h"
#include "core/mapping/occupancy_grid.h"

namespace coopmap {

struct MapMetrics {
  // Fraction of true occupied cells next to observed free space (truly free cells the map
  // has seen) that have an occupied map cell within 1 cell (8-neighbourhood).
  double wall_recall = 0.0;
  // Fraction of observed true-free cells more than 1 cell from any true obstacle that the
  // map marks occupied.
  double false_occupied_rate = 0.0;
  // Fraction of the true free area reachable from the start cell (4-connected) that the
  // map has observed.
  double coverage = 0.0;
  // false_occupied_rate split by how far (cells, chessboard) each false obstacle lies from
  // the nearest true one: 2 (a wall drawn a cell thick or off), 3, 4-5, 6-10, 11 and more
  // (obstacles where there are none). Same denominator: the five sum to the rate.
  static constexpr int kDistanceBands = 5;
  static constexpr const char* kDistanceBandNames[kDistanceBands] = {"2", "3", "4-5", "6-10",
                                                                     "11+"};
  std::array<double, kDistanceBands> false_occupied_by_distance{};
  int wall_cells = 0;            // denominator of wall_recall
  int clear_observed_cells = 0;  // denominator of false_occupied_rate
  int reachable_cells = 0;       // denominator of coverage
};

// `truth` holds 1 for occupied cells and 0 for free ones; `start` is a world position
// inside the reachable free space; `drivable`, if given, is 1 where the world has a floor:
// free cells off the floor (outside the building) count neither as free space nor as
// reachable. Throws std::invalid_argument if the limits differ.
MapMetrics computeMapMetrics(const OccupancyGrid& map, const GridU8& truth,
                             const Eigen::Vector2d& start, const GridU8* drivable = nullptr);

// Cells of `truth` that are free, drivable and 4-connected to `start` (1 = reachable).
GridU8 reachableFree(const GridU8& truth, const Eigen::Vector2d& start,
                     const GridU8* drivable = nullptr);

}  // namespace coopmap
