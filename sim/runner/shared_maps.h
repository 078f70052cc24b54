// The shared maps of a run, built from what its agents logged (sim/runner/world_run.h):
// the home-base protocol's (the live one of a cooperative run, or the scripted robots'
// traverses run through it afterwards) and the naive one, every radial map at its odometry
// pose, for comparison; each scored against the truth.
#pragma once

#include <string>
#include <vector>

#include "core/agent/robot_agent.h"
#include "core/sharing/shared_map.h"
#include "sim/runner/world_run.h"

namespace coopmap {

// Adds `b`'s evidence to `a` (log-odds summed and clamped, seen where either has seen).
void mergeSeen(OccupancyGrid& a, const OccupancyGrid& b);

// The naive shared map: every radial map of every placed agent at its encoders' odometry,
// placed in the map frame by the agent's first look only. `published`: the shared map's
// published update rule (LocalSharedMap).
OccupancyGrid naiveSharedMap(const MapLimits& limits, const std::vector<const RobotAgent*>& agents,
                             const OccupancyConfig& published);

// A cooperative run's shared maps: the live one the agents posted to, and the naive one;
// scored against `truth` and `floor` from the true start `start` (map frame).
SharedMapResult cooperativeSharedMaps(const LocalSharedMap& live,
                                      const std::vector<const RobotAgent*>& agents,
                                      const MapLimits& limits, const OccupancyConfig& published,
                                      const GridU8& truth, const GridU8& floor, const Pose2& start);

// After a run of routes: each agent's whole traverse as one sortie of the home-base protocol
// (HomeBaseCooperation: localized at the home base `design`, corrected with the paper's
// heading-drift model and the loop closures `closures` names, checked against what is already
// shared, posted), and the naive map; both the published grids of `published`'s rule.
SharedMapResult shareMaps(const HomeBaseDesign& design, const MapLimits& limits,
                          const GridU8& floor, const GridU8& truth,
                          const std::vector<const RobotAgent*>& agents, const std::string& closures,
                          const OccupancyConfig& published, const Pose2& start);

}  // namespace coopmap
