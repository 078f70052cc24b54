// Checks that a world can be explored from its robots' starts: every floor cell reachable
// through openings the robot fits, the starts clear of every solid, and the home base's two
// corners in view from each start. The world generator (world_generator.h) keeps only worlds
// that pass; they serve any hand-written world too.
#pragma once

#include <string>

#include "sim/world/world.h"

namespace coopmap::sim {

struct WorldCheckLimits {
  double robot_radius = 0.25;         // m, the B-14 body with its bumpers
  double margin = 0.05;               // m added to the radius for reachability
  double start_clearance = 0.10;      // m between a start's robot body and any solid
  double cell = 0.05;                 // m, raster of the reachability check
  double min_start_separation = 1.0;  // m between two robots' starts
  double min_home_distance = 1.0;     // m from a start to the home base's middle
  double max_home_distance = 2.5;     // m
  double view_half_angle_deg = 43.0;  // a start must lie this close to a corner's heading
};

enum class WorldCheckStatus {
  kOk,
  kStartBlocked,      // a start within robot_radius + start_clearance of a solid, or off the floor
  kStartsTooClose,    // two starts closer than min_start_separation
  kHomeBaseDistance,  // a start nearer or farther from the home base than allowed
  kHomeBaseHidden,    // a corner's vertex hidden from a start, or seen from outside its L
  kUnreachableFloor,  // free floor cells that no start reaches
};

struct WorldCheckResult {
  WorldCheckStatus status = WorldCheckStatus::kOk;
  std::string detail;  // what failed and where (m, world frame); empty if ok
  bool ok() const { return status == WorldCheckStatus::kOk; }
};

// Runs every check, in the order of WorldCheckStatus, and returns the first failure.
WorldCheckResult checkWorldExplorable(const World& world, const WorldCheckLimits& limits = {});

// Distance (m) from point p to a solid box's footprint (0 inside).
double distanceToFootprint(const SolidBox& box, const Eigen::Vector2d& p);

}  // namespace coopmap::sim
