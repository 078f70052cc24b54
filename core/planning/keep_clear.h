// Paths that keep clear of walls where the map leaves room. The planner's map guarantees
// the robot's radius plus a margin around every blocked cell; a path string-pulled around
// corners and along walls keeps no more than that, and a robot whose estimate is 0.2 m off
// across a corridor scrapes the real wall. keepClear bends such a path away from what is
// blocked, up to a preferred clearance, wherever the map has room for it; in a door no
// wider than the robot needs, the path still goes through.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/planning/planning_map.h"

namespace coopmap {

struct KeepClearConfig {
  double clearance = 0.0;  // m from blocked cells' centres the path keeps where it can
  // m of clearance a path is expected to gain per m away from an end near a wall: leaving
  // the wall at about 27 degrees, not straight out from it.
  double ramp = 0.5;
  int max_added = 8;  // waypoints added at most (each one is a turn in place)
  int passes = 8;     // rounds of moving and adding waypoints
};

// Clearance of the map (PlanningMap::clearance, between cell centres) at a world point,
// interpolated bilinearly between cell centres; cells outside the map count 0.
double clearanceAt(const PlanningMap& map, const Eigen::Vector2d& p);

// How far a polyline falls short of the clearance it could keep: the integral along it of
// max(0, cap(p) - clearanceAt(p)) (m^2), where cap(p) = min(clearance, clearance of `from`
// + ramp |p - from|, clearance of `to` + ramp |p - to|) for the path's fixed ends `from` and
// `to` (near an end that is itself near a wall, no path is clearer than that end allows);
// and the largest such shortfall (m).
struct Shortfall {
  double integral = 0.0;
  double worst = 0.0;
};
Shortfall shortfallOf(const std::vector<Eigen::Vector2d>& waypoints, const PlanningMap& map,
                      const KeepClearConfig& config);

// The path bent away from blocked cells: waypoints moved up the clearance map, and new
// ones added where a segment runs close to something, each change accepted only if it
// keeps every segment free on `map` and reduces the path's shortfall. The first and last
// waypoints stay. Precondition: every segment of `waypoints` is free on `map`
// (PlanningMap::segmentFree); so is every segment of the result. Deterministic.
std::vector<Eigen::Vector2d> keepClear(std::vector<Eigen::Vector2d> waypoints,
                                       const PlanningMap& map, const KeepClearConfig& config);

}  // namespace coopmap
