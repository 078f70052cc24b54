// Queries the mission's parts share on the maps and the ways they plan (core/agent/mission.h):
// the free cells a robot steps off to or heads for when it cannot plan where it wants, how
// near a point lies to the way ahead, and the route along a planned path. Map frame, m.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "core/agent/route_follower.h"
#include "core/planning/planning_map.h"

namespace coopmap {

// The free cell nearest `from` within `within` (m) on `planning`, if any.
std::optional<Eigen::Vector2d> nearestFreeCell(const PlanningMap& planning,
                                               const Eigen::Vector2d& from, double within);
// A waypoint onto the free cell centred at `centre` of a map at `resolution` (m) that counts
// as reached only inside that cell: the route's arrival tolerance can be as wide as a cell, and
// a robot "arrived" within it can still stand on the blocked cell it was stepping off.
Waypoint ontoCell(const Eigen::Vector2d& centre, double resolution);
// The free cell of `from`'s region nearest `to`, if it is at least 0.5 m nearer `to` than
// `from` is.
std::optional<Eigen::Vector2d> nearestReachable(const PlanningMap& planning,
                                                const Eigen::Vector2d& from,
                                                const Eigen::Vector2d& to);
// `p` lies within `within` (m) of the polyline `way`.
bool nearWay(const std::vector<Eigen::Vector2d>& way, const Eigen::Vector2d& p, double within);
// The route through a path's waypoints after the first (where the robot stands).
std::vector<Waypoint> routeAlong(const std::vector<Eigen::Vector2d>& waypoints);

}  // namespace coopmap
