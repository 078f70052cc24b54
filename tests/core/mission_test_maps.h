// Shared by the mission tests: a kinematic robot's looks and maps, and a quick mission.
#pragma once

#include <cmath>

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

// Free space 3.5 m ahead of `at` over +-60 degrees (a look that way); unknown beyond.
inline OccupancyGrid lookedAround(const Pose2& at) {
  OccupancyGrid map(MapLimits::covering({0.0, 0.0}, {8.0, 6.0}, 0.05), OccupancyConfig{});
  const RadialMap scan = freeAhead(3.5);
  for (int k = -3; k <= 3; ++k)
    for (int i = 0; i < 3; ++i) map.insert(scan, Pose2(at.x, at.y, at.theta + k * M_PI / 18.0));
  return map;
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
