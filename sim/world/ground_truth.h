// Ground truth the simulator knows: the true occupancy of the world at map resolution, in
// a map frame placed in the world at X_WM (the home base's frame; identity: the world's).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/geometry/pose2.h"
#include "core/localization/home_base.h"
#include "core/mapping/grid.h"
#include "sim/world/world.h"

namespace coopmap::sim {

// The world's home base as a design: its corners, arms and thickness in the world frame.
// Throws std::invalid_argument unless the world has one (two corners).
HomeBaseDesign homeBaseInWorld(const World& world);

// X_WM: where the map frame that `design` defines stands in the world, from where the world
// puts its home base (the first corner on the design's first). Throws std::invalid_argument
// naming what differs when the world's home base is not built as designed (corner spacing
// or turn off by more than 1 cm or 1 degree, other arms or thickness).
Pose2 mapFrameInWorld(const World& world, const HomeBaseDesign& design);

// Map limits (map frame) covering the world's floor with a margin (m).
MapLimits worldMapLimits(const World& world, double margin = 0.5, const Pose2& X_WM = {});

// 1 where a solid occupies any part of the cell between the floor and `max_height` (m):
// each cell is sampled at 4x4 points, so partly covered cells count as occupied.
GridU8 trueOccupancy(const World& world, const MapLimits& limits, double max_height,
                     const Pose2& X_WM = {});

// The true occupancy at time t (s): the static solids plus the doors closed at t and the
// people standing at `people` (m, world; one position per world.people, in order: a
// simulation's Simulator::personPositions() at t). Throws std::invalid_argument if the
// count differs.
GridU8 trueOccupancyAt(const World& world, const MapLimits& limits, double max_height, double t,
                       const std::vector<Eigen::Vector2d>& people, const Pose2& X_WM = {});

// As above with the people where their schedule puts them at t if no robot ever made them
// wait (PersonSpec::positionAt). In a simulation with robots near people, use the overload
// above with the simulator's positions.
GridU8 trueOccupancyAt(const World& world, const MapLimits& limits, double max_height, double t);

// 1 for cells whose centre lies on the floor (where a robot can be at all).
GridU8 floorMask(const World& world, const MapLimits& limits, const Pose2& X_WM = {});

// True if the world point lies inside the footprint of the box (m).
bool insideFootprint(const SolidBox& box, const Eigen::Vector2d& p);

}  // namespace coopmap::sim
