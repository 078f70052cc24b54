// Follows a scripted route the way the paper's robots drive: turn in place towards the
// next waypoint, drive straight to it, optionally spin a full turn there to look around.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/pose2.h"
#include "core/io/yaml_reader.h"
#include "core/robot/robot_interface.h"

namespace coopmap {

struct Waypoint {
  Eigen::Vector2d position{0.0, 0.0};  // m, odometry (map) frame
  bool spin = false;                   // turn a full circle on arrival
  double spin_rate = 0.0;              // rad/s for that turn; 0: the route's turn rate
  double wait = 0.0;                   // s to stand still on arrival (before a spin)
  // rad, odometry (map) frame: on arrival, first turn in place to this heading (then wait,
  // then spin). A look at the home base this way starts as the start's look did.
  std::optional<double> face = std::nullopt;
  double face_within = 0.0;       // rad: `face` turned to within this; 0: the route's
  double arrive_tolerance = 0.0;  // m: arrived within this; 0: the route's
};

struct RouteConfig {
  double linear_speed = 0.4;        // m/s cruise
  double angular_speed = 0.7;       // rad/s for turns in place
  double heading_tolerance = 0.03;  // rad: turn until within this, then drive
  double face_tolerance = 0.003;    // rad: a waypoint's `face` heading is turned to this well
  double arrive_tolerance = 0.05;   // m
  double heading_gain = 2.0;        // rad/s per rad of heading error while driving
  // rad/s^2: a turn in place slows down no harder than this as it nears its heading (its rate
  // at most sqrt(2 * angular_decel * error)), so it stops there as the base can stop it. 0:
  // the rate falls in proportion to the error (heading_gain), never below 0.1 rad/s: the
  // last tenths of a radian take a second.
  double angular_decel = 0.0;
  void validate() const;  // throws std::invalid_argument naming the field
};

// `cmd` with its linear speed raised from `previous` (m/s, the last command's) by at most
// accel * dt (m/s^2, s); a command the other way starts from a standstill. Slowing down and
// stopping are not limited (a stop is a stop). Turns and straight segments, and accel 0, pass
// as they are.
MotionCommand limitSpeedUp(MotionCommand cmd, double previous, double accel, double dt);

// A waypoint from YAML: `[x, y]` or
// `{at: [x, y], within: m, face_deg: h, wait: s, spin: true, spin_rate_deg: d}`;
// ConfigError naming the file, line and field otherwise.
Waypoint parseWaypoint(const YamlField& f);

class RouteFollower {
 public:
  RouteFollower(std::vector<Waypoint> route, const RouteConfig& config);

  // The command for the current odometry pose at time `now` (s, robot clock; only waits
  // need it); call at the control rate.
  MotionCommand update(const Pose2& pose, double now = 0.0);
  bool done() const { return next_ >= route_.size(); }
  size_t nextWaypoint() const { return next_; }

 private:
  enum class Phase { kTurn, kDrive, kFace, kWait, kSpin };
  MotionCommand arrived(const Waypoint& wp, const Pose2& pose, double now);  // at the waypoint
  double turnRate(double error) const;  // rad/s of a turn in place `error` (rad) from its heading
  void afterWait(const Waypoint& wp, const Pose2& pose);  // arrived and waited: spin or go on
  std::vector<Waypoint> route_;
  RouteConfig config_;
  size_t next_ = 0;
  Phase phase_ = Phase::kTurn;
  double spin_done_ = 0.0;  // rad turned so far in a spin
  double last_theta_ = 0.0;
  double wait_until_ = 0.0;  // s, end of the current wait
};

}  // namespace coopmap
