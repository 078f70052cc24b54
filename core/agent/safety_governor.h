// The mission's safety governor (core/agent/mission.h): what keeps the robot off what its
// cameras and bumpers find, whatever its plan says. It slows the robot for what is near ahead
// in the latest radial map (slow_distance), stops it for what is nearer than safety_distance,
// backs it off after a bump (backoff_s), and limits how fast it speeds up (max_linear_accel).
// It counts these safety stops, and the bumps of a sortie.
#pragma once

#include <optional>

#include "core/agent/mission_config.h"
#include "core/perception/radial_map.h"
#include "core/robot/robot_interface.h"

namespace coopmap {

class SafetyGovernor {
 public:
  explicit SafetyGovernor(const MissionConfig& config);

  // Takes the nearest hit ahead (within safety_half_angle) of the latest radial map.
  void see(const RadialMap& latest);
  // Driving forwards at `linear` (m/s, > 0), an obstacle nearer than safety_distance ahead
  // in `latest` (nullptr: no new radial map) stops the robot: true, counted as a safety stop.
  bool mustStop(const RadialMap* latest, double linear);
  // `cmd` with its forward speed capped by the nearest obstacle ahead (slow_distance).
  MotionCommand slowed(MotionCommand cmd) const;
  // `cmd` speeding up no faster than max_linear_accel from the last command this returned;
  // remembers it as sent at `now` (s).
  MotionCommand limitSpeedUp(const MotionCommand& cmd, double now);

  // Backing off from a bump until a moment after `now` (s).
  bool backingOff(double now) const { return now < backoff_until_; }
  // Neither backing off nor done with a back-off not yet taken up (backOffDone): a bump now
  // starts a back-off.
  bool canBackOff() const { return backoff_until_ < 0.0; }
  // A bump at `now`: back off for backoff_s (counted as a safety stop). Returns the bearing
  // (rad, robot frame) of what was touched, if known: the base's `bump_bearing` (bump_away),
  // else straight ahead or behind by the sign of `linear`, the last command's (m/s).
  std::optional<double> backOff(double now, std::optional<double> bump_bearing, double linear);
  // The command while backing off: away from the touch at 0.1 m/s.
  MotionCommand backoffCommand() const { return MotionCommand{backoff_speed_, 0.0}; }
  // The back-off is over at `now`: true once, and the bump counts for the sortie.
  bool backOffDone(double now);
  int sortieBumps() const { return sortie_bumps_; }
  void startSortie() { sortie_bumps_ = 0; }

  int stops() const { return stops_; }

 private:
  bool obstacleAhead(const RadialMap& scan) const;

  MissionConfig config_;
  double nearest_ahead_ = 1e9;   // m: the nearest hit ahead in the latest radial map
  double backoff_until_ = -1.0;  // s: backing off until then (negative: not)
  double backoff_speed_ = -0.1;  // m/s while backing off from a bump
  int sortie_bumps_ = 0;         // back-offs done this sortie
  int stops_ = 0;                // safety stops: obstacles ahead and bumps
  double sent_linear_ = 0.0;     // m/s: the linear speed of the last command sent
  double sent_at_ = -1.0;        // s: when (negative: none yet)
};

}  // namespace coopmap
