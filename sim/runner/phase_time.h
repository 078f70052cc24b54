// The time a robot's agent spent in one of its phases, and how the robot moved meanwhile: a
// run's account of where its time went (metrics.json "phases", explore.md).
#pragma once

#include <string>

namespace coopmap {

struct PhaseTime {
  std::string phase;  // the agent's phase (RobotAgent::phase())
  double time_s = 0.0;
  double driving_s = 0.0;  // moving faster than 3 cm/s (the truth's motion)
  double turning_s = 0.0;  // not driving, and turning faster than 0.05 rad/s: in place
  double path_m = 0.0;
};

}  // namespace coopmap
