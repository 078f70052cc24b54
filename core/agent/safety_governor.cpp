#include "core/agent/safety_governor.h"

#include <algorithm>
#include <cmath>

#include "core/agent/route_follower.h"

namespace coopmap {

SafetyGovernor::SafetyGovernor(const MissionConfig& config) : config_(config) {}

void SafetyGovernor::see(const RadialMap& latest) {
  nearest_ahead_ = 1e9;
  for (const RadialReading& r : latest.readings)
    if (r.kind == RadialKind::kHit && std::abs(r.bearing) < config_.safety_half_angle)
      nearest_ahead_ = std::min(nearest_ahead_, r.range);
}

bool SafetyGovernor::obstacleAhead(const RadialMap& scan) const {
  for (const RadialReading& r : scan.readings)
    if (r.kind == RadialKind::kHit && r.range < config_.safety_distance &&
        std::abs(r.bearing) < config_.safety_half_angle)
      return true;
  return false;
}

bool SafetyGovernor::mustStop(const RadialMap* latest, double linear) {
  if (!(linear > 0.0 && latest && obstacleAhead(*latest))) return false;
  ++stops_;
  return true;
}

MotionCommand SafetyGovernor::slowed(MotionCommand cmd) const {
  if (config_.slow_distance <= config_.safety_distance || cmd.linear <= 0.0) return cmd;
  const double f = std::clamp((nearest_ahead_ - config_.safety_distance) /
                                  (config_.slow_distance - config_.safety_distance),
                              config_.slow_fraction, 1.0);
  cmd.linear = std::min(cmd.linear, f * config_.route.linear_speed);
  return cmd;
}

MotionCommand SafetyGovernor::limitSpeedUp(const MotionCommand& cmd, double now) {
  const MotionCommand sent = coopmap::limitSpeedUp(cmd, sent_linear_, config_.max_linear_accel,
                                                   sent_at_ < 0.0 ? 0.0 : now - sent_at_);
  sent_linear_ = sent.kind == MotionCommand::Kind::kVelocity ? sent.linear : 0.0;
  sent_at_ = now;
  return sent;
}

std::optional<double> SafetyGovernor::backOff(double now, std::optional<double> bump_bearing,
                                              double linear) {
  ++stops_;
  backoff_until_ = now + config_.backoff_s;
  backoff_speed_ = -0.1;
  std::optional<double> bearing;
  if (config_.bump_away && bump_bearing) {
    bearing = *bump_bearing;
    if (std::cos(*bearing) < 0.0) backoff_speed_ = 0.1;  // touched behind: away is forwards
  } else if (linear != 0.0) {
    bearing = linear > 0.0 ? 0.0 : M_PI;
  }
  return bearing;
}

bool SafetyGovernor::backOffDone(double now) {
  if (!(backoff_until_ >= 0.0 && now >= backoff_until_)) return false;
  backoff_until_ = -1.0;
  ++sortie_bumps_;
  return true;
}

}  // namespace coopmap
