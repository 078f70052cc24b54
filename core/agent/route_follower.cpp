#include "core/agent/route_follower.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/robot/braking.h"

namespace coopmap {

void RouteConfig::validate() const {
  auto bad = [](const std::string& f, double v) {
    throw std::invalid_argument("route config: field '" + f +
                                "': expected a positive number, got " + std::to_string(v));
  };
  if (!(linear_speed > 0.0)) bad("linear_speed", linear_speed);
  if (!(angular_speed > 0.0)) bad("angular_speed", angular_speed);
  if (!(heading_tolerance > 0.0)) bad("heading_tolerance", heading_tolerance);
  if (!(face_tolerance > 0.0)) bad("face_tolerance", face_tolerance);
  if (!(arrive_tolerance > 0.0)) bad("arrive_tolerance", arrive_tolerance);
  if (!(heading_gain > 0.0)) bad("heading_gain", heading_gain);
  if (!(angular_decel >= 0.0))
    throw std::invalid_argument(
        "route config: field 'angular_decel': expected a number >= 0, got " +
        std::to_string(angular_decel));
}

MotionCommand limitSpeedUp(MotionCommand cmd, double previous, double accel, double dt) {
  if (cmd.kind != MotionCommand::Kind::kVelocity || accel <= 0.0) return cmd;
  const double from = cmd.linear * previous > 0.0 ? std::abs(previous) : 0.0;
  const double limit = from + accel * std::max(dt, 0.0);
  if (std::abs(cmd.linear) > limit) cmd.linear = std::copysign(limit, cmd.linear);
  return cmd;
}

Waypoint parseWaypoint(const YamlField& f) {
  Waypoint wp;
  if (f.isSequence()) {
    wp.position = f.asVector2();
    return wp;
  }
  if (!f.isMap()) f.fail("a waypoint: [x, y] or {at: [x, y], spin: true}");
  f.allowOnly({"at", "within", "face_deg", "wait", "spin", "spin_rate_deg"});
  wp.position = f["at"].asVector2();
  if (f.has("within"))
    wp.arrive_tolerance = f["within"].asDouble(0.001, 10.0, "metres in [0.001, 10]");
  if (f.has("face_deg"))
    wp.face = f["face_deg"].asDouble(-360.0, 360.0, "a heading in [-360, 360] deg") * M_PI / 180.0;
  if (f.has("wait")) wp.wait = f["wait"].asDouble(0.0, 600.0, "seconds in [0, 600]");
  if (f.has("spin")) wp.spin = f["spin"].asBool();
  if (f.has("spin_rate_deg"))
    wp.spin_rate =
        f["spin_rate_deg"].asDouble(1.0, 180.0, "a turn rate in [1, 180] deg/s") * M_PI / 180.0;
  return wp;
}

RouteFollower::RouteFollower(std::vector<Waypoint> route, const RouteConfig& config)
    : route_(std::move(route)), config_(config) {
  config_.validate();
}

MotionCommand RouteFollower::arrived(const Waypoint& wp, const Pose2& pose, double now) {
  if (wp.wait > 0.0) {
    phase_ = Phase::kWait;
    wait_until_ = now + wp.wait;
    return MotionCommand::stop();
  }
  afterWait(wp, pose);
  return MotionCommand::stop();
}

double RouteFollower::turnRate(double error) const {
  if (config_.angular_decel > 0.0)
    return std::copysign(brakingSpeed(error, config_.angular_decel, config_.angular_speed), error);
  const double w =
      std::clamp(config_.heading_gain * error, -config_.angular_speed, config_.angular_speed);
  // Keep a minimum turn rate so the robot does not crawl into the tolerance.
  const double min_w = 0.1;
  return std::abs(w) < min_w ? std::copysign(min_w, error) : w;
}

void RouteFollower::afterWait(const Waypoint& wp, const Pose2& pose) {
  if (wp.spin) {
    phase_ = Phase::kSpin;
    spin_done_ = 0.0;
    last_theta_ = pose.theta;
    return;
  }
  ++next_;
  phase_ = Phase::kTurn;
}

MotionCommand RouteFollower::update(const Pose2& pose, double now) {
  while (next_ < route_.size()) {
    const Waypoint& wp = route_[next_];
    const Eigen::Vector2d to = wp.position - pose.translation();
    const double dist = to.norm();
    const double bearing_err = wrapAngle(std::atan2(to.y(), to.x()) - pose.theta);
    const double arrive =
        wp.arrive_tolerance > 0.0 ? wp.arrive_tolerance : config_.arrive_tolerance;
    switch (phase_) {
      case Phase::kTurn:
        if (dist < arrive) {
          phase_ = Phase::kDrive;
          continue;
        }
        if (std::abs(bearing_err) > config_.heading_tolerance) return {0.0, turnRate(bearing_err)};
        phase_ = Phase::kDrive;
        continue;
      case Phase::kDrive: {
        // Arrived, or passed the waypoint (it is now behind the robot).
        if (dist < arrive || std::abs(bearing_err) > M_PI / 2) {
          if (wp.face) {
            phase_ = Phase::kFace;
            continue;
          }
          const MotionCommand c = arrived(wp, pose, now);
          if (phase_ == Phase::kWait) return c;
          continue;
        }
        if (std::abs(bearing_err) > 0.35) {  // knocked off course: turn in place again
          phase_ = Phase::kTurn;
          continue;
        }
        const double v = std::min(config_.linear_speed, std::max(0.1, 1.5 * dist));
        const double w = std::clamp(config_.heading_gain * bearing_err, -config_.angular_speed,
                                    config_.angular_speed);
        return {v, w};
      }
      case Phase::kFace: {
        // Slowly at the end, to within face_tolerance: a look that starts as the start's did
        // sees the same things in the same image columns.
        const double err = wrapAngle(*wp.face - pose.theta);
        if (wp.face_within >= config_.heading_tolerance && std::abs(err) > wp.face_within)
          return {0.0, turnRate(err)};  // a look's heading, as coarse as a turn's
        if (std::abs(err) > (wp.face_within > 0.0 ? wp.face_within : config_.face_tolerance)) {
          const double w =
              std::clamp(config_.heading_gain * err, -config_.angular_speed, config_.angular_speed);
          return {0.0, std::abs(w) < 0.02 ? std::copysign(0.02, err) : w};
        }
        const MotionCommand c = arrived(wp, pose, now);
        if (phase_ == Phase::kWait) return c;
        continue;
      }
      case Phase::kWait:
        if (now < wait_until_ - 1e-9) return MotionCommand::stop();
        afterWait(wp, pose);
        continue;
      case Phase::kSpin:
        spin_done_ += wrapAngle(pose.theta - last_theta_);
        last_theta_ = pose.theta;
        if (spin_done_ >= 2.0 * M_PI) {
          ++next_;
          phase_ = Phase::kTurn;
          continue;
        }
        return {0.0, wp.spin_rate > 0.0 ? wp.spin_rate : config_.angular_speed};
    }
  }
  return MotionCommand::stop();
}

}  // namespace coopmap
