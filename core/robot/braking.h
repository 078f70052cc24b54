// The speed a base may hold and still stop where it should: shared by the turn and segment
// profiles of the agents, the simulator and the drivers.
#pragma once

#include <algorithm>
#include <cmath>

namespace coopmap {

// The largest speed (m/s or rad/s) from which braking at `decel` (per s) stops within
// `remaining` (m or rad, either sign), and at most `max_speed`.
inline double brakingSpeed(double remaining, double decel, double max_speed) {
  return std::min(max_speed, std::sqrt(2.0 * decel * std::abs(remaining)));
}

}  // namespace coopmap
