// Shared by the mission tests (and the planning tests on the same maps): a kinematic robot's
// looks and maps, and a quick mission.
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/agent/mission.h"
#include "core/geometry/pose2.h"
#include "core/mapping/occupancy_grid.h"
#include "core/perception/radial_map.h"

namespace coopmap::mission_test {

// A radial map of 40 columns over +-60 degrees, free up to `range` (m) in every one.
inline RadialMap freeAhead(double range) {
  RadialMap scan;
  scan.max_range = range;
  for (int c = 0; c < 40; ++c) {
    RadialReading r;
    r.bearing = (c - 19.5) / 39.0 * (M_PI / 3.0);
    r.range = range;
    r.kind = RadialKind::kBeyond;
    scan.readings.push_back(r);
  }
  return scan;
}

// A radial map with one obstacle straight ahead at `range` (m), or none.
inline RadialMap aheadAt(std::optional<double> range) {
  RadialMap scan = freeAhead(4.0);
  for (RadialReading& r : scan.readings)
    if (range && std::abs(r.bearing) < 0.1) {
      r.range = *range;
      r.kind = RadialKind::kHit;
    }
  return scan;
}

// Free space 3.5 m ahead of `at` over +-60 degrees (a look that way); unknown beyond.
inline OccupancyGrid lookedAround(const Pose2& at) {
  OccupancyGrid map(MapLimits::covering({0.0, 0.0}, {8.0, 6.0}, 0.05), OccupancyConfig{});
  const RadialMap scan = freeAhead(3.5);
  for (int k = -3; k <= 3; ++k)
    for (int i = 0; i < 3; ++i) map.insert(scan, Pose2(at.x, at.y, at.theta + k * M_PI / 18.0));
  return map;
}

// A grid over `lim` whose cell with centre c holds log-odds `cell(c)`, observed, or is never
// observed where `cell(c)` is nothing.
template <typename Cell>
OccupancyGrid gridOf(const MapLimits& lim, Cell cell) {
  OccupancyGrid g(lim, OccupancyConfig{});
  std::vector<int16_t> lo(lim.size(), 0);
  std::vector<uint8_t> seen(lim.size(), 0);
  for (int iy = 0; iy < lim.height; ++iy)
    for (int ix = 0; ix < lim.width; ++ix)
      if (const std::optional<int16_t> l = cell(lim.cellCenter(ix, iy))) {
        lo[lim.index(ix, iy)] = *l;
        seen[lim.index(ix, iy)] = 1;
      }
  g.assign(lo, seen);
  return g;
}

// A 6 m x 4 m map at 5 cm: a walled room x in [0, 3] m with a doorway y in [1.5, 2.5] m in its
// east wall, a corridor x in [3, seen_to] m seen beyond it, and nothing seen east of that. When
// `person_in_door`, the map holds an obstacle 0.3 m x 0.5 m in the doorway's middle (someone
// who stood there), leaving gaps too narrow for the robot either side.
inline OccupancyGrid roomAndCorridor(bool person_in_door, double seen_to = 4.5) {
  const MapLimits lim = MapLimits::covering({0.0, 0.0}, {6.0, 4.0}, 0.05);
  return gridOf(lim, [&](const Eigen::Vector2d& c) -> std::optional<int16_t> {
    if (c.x() > seen_to) return std::nullopt;
    const bool east_wall = c.x() > 2.95 && c.x() < 3.05 && (c.y() < 1.5 || c.y() > 2.5);
    const bool room_wall = c.x() < 3.0 && (c.x() < 0.1 || c.y() < 0.1 || c.y() > 3.9);
    const bool person =
        person_in_door && c.x() > 2.95 && c.x() < 3.25 && c.y() > 1.75 && c.y() < 2.25;
    return east_wall || room_wall || person ? 1000 : -1000;
  });
}

// Quick looks at home (a short wait, a fast turn): the tests are about what comes after.
inline MissionConfig quickLooks() {
  MissionConfig c;
  c.look_wait_s = 0.2;
  c.look_turn_rate = 3.0;
  return c;
}

// Quick looks at home and a first sortie that ends after 0.5 m, of two sorties: the tests
// below carry the robot elsewhere as it sets off, and watch its way home.
inline MissionConfig quickFirstSortie() {
  MissionConfig c = quickLooks();
  c.first_budget_m = 0.5;
  c.max_sorties = 2;
  c.planner.seed = 5;
  return c;
}

}  // namespace coopmap::mission_test
