// The time a robot's agent spent in one of its phases, and how the robot moved meanwhile: a
// run's account of where its time went (metrics.json "phases", explore.md).
#pragma once

#include <algorithm>
#include <string>
#include <vector>

namespace coopmap {

struct PhaseTime {
  std::string phase;  // the agent's phase (RobotAgent::phase())
  double time_s = 0.0;
  double driving_s = 0.0;  // moving faster than 3 cm/s (the truth's motion)
  double turning_s = 0.0;  // not driving, and turning faster than 0.05 rad/s: in place
  double path_m = 0.0;

  // Another account's times and path added to this one's.
  PhaseTime& operator+=(const PhaseTime& o) {
    time_s += o.time_s;
    driving_s += o.driving_s;
    turning_s += o.turning_s;
    path_m += o.path_m;
    return *this;
  }
};

// The account of `phase` in `phases`, appended (empty) when there is none yet.
inline PhaseTime& phaseNamed(std::vector<PhaseTime>& phases, const std::string& phase) {
  auto in = std::find_if(phases.begin(), phases.end(),
                         [&](const PhaseTime& t) { return t.phase == phase; });
  return in != phases.end() ? *in : phases.emplace_back(PhaseTime{phase});
}

}  // namespace coopmap
