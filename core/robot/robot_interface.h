// The one robot interface: the simulator, a log replayer and a real B-14 each implement it,
// and the core (agent, mapping) sees nothing else of them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "core/geometry/camera.h"
#include "core/geometry/pose2.h"

namespace coopmap {

// Static description of a robot: body, limits and camera rig.
struct RobotDescription {
  std::string model = "b14";
  double body_radius = 0.178;      // m (14-inch diameter cylinder)
  double body_height = 0.80;       // m, top of the base
  double swept_height = 1.00;      // m, everything up to here can hit the robot
  double max_linear_speed = 0.9;   // m/s
  double max_angular_speed = 1.6;  // rad/s
  double max_linear_accel = 1.0;   // m/s^2
  double max_angular_accel = 3.0;  // rad/s^2
  TrinocularRig rig;
};

// Three rectified 8-bit images captured together, with the odometry pose at capture.
struct TrinocularFrame {
  double stamp = 0.0;  // s, robot clock
  Pose2 odometry;      // X_OR: robot in the odometry frame at capture
  cv::Mat reference;   // CV_8UC1
  cv::Mat horizontal;  // CV_8UC1, partner offset by rig.horizontal_offset
  cv::Mat vertical;    // CV_8UC1, partner offset by rig.vertical_offset
};

// A planar range scan (a laser, or any sensor of ranges along a fan of rays) with the
// odometry pose at capture. Beam i leaves sensor_origin at bearing
// start_angle + i * angular_resolution in the robot frame (CCW from +x), so a sensor mounted
// turned adds its yaw to start_angle.
struct RangeScan {
  double stamp = 0.0;                       // s, robot clock
  Pose2 odometry;                           // X_OR: robot in the odometry frame at capture
  double start_angle = 0.0;                 // rad, bearing of beam 0 in the robot frame
  double angular_resolution = 0.0;          // rad from one beam to the next (CCW positive)
  double max_range = 0.0;                   // m; a reading at or beyond it is "no return"
  double range_sigma = 0.01;                // m, 1-sigma range noise
  Eigen::Vector2d sensor_origin{0.0, 0.0};  // m, where the beams start, in the robot frame
  std::vector<float> ranges;                // m per beam; <= 0 or not finite: invalid

  // Bearing of beam i in the robot frame (rad).
  double bearing(size_t i) const {
    return start_angle + static_cast<double>(i) * angular_resolution;
  }
};

// A motion command, held until the next: a velocity (v, omega), or a segment the base
// executes by its own encoders, the way the paper's robots moved: turn in place by an
// angle, or drive straight a distance; then it stops.
struct MotionCommand {
  enum class Kind : uint8_t { kVelocity, kTurn, kStraight };
  double linear = 0.0;   // m/s, along robot +x (kVelocity)
  double angular = 0.0;  // rad/s, CCW (kVelocity)
  Kind kind = Kind::kVelocity;
  double amount = 0.0;  // kTurn: rad, CCW positive; kStraight: m, negative backwards

  static MotionCommand stop() { return {}; }
  static MotionCommand turn(double rad) { return {0.0, 0.0, Kind::kTurn, rad}; }
  static MotionCommand straight(double m) { return {0.0, 0.0, Kind::kStraight, m}; }
};

// What the base reports besides odometry.
struct RobotStatus {
  bool bumped = false;          // touching an obstacle now
  int contact_events = 0;       // count of distinct contacts since start
  bool segment_active = false;  // a turn or straight segment is under way
  // rad, robot frame (CCW from ahead): where the base is touched, if it says (the B-14's
  // bump panels ring the base; a base reporting only "pressed" leaves it empty).
  std::optional<double> bump_bearing;
};

class RobotInterface {
 public:
  virtual ~RobotInterface() = default;
  RobotInterface() = default;
  RobotInterface(const RobotInterface&) = delete;
  RobotInterface& operator=(const RobotInterface&) = delete;

  // The robot's static description (valid for the robot's lifetime).
  virtual const RobotDescription& description() const = 0;
  // Current time on the robot's clock (s).
  virtual double now() const = 0;
  // Captures a trinocular frame now; nullopt when the cameras have nothing (yet).
  virtual std::optional<TrinocularFrame> captureFrame() = 0;
  // Captures the next planar range scan; nullopt when there is none (yet), or when the
  // robot has no range sensor (the default).
  virtual std::optional<RangeScan> captureScan() { return std::nullopt; }
  // Odometry pose X_OR now (m, rad).
  virtual Pose2 odometry() const = 0;
  // Sets the motion command; held until replaced. Limits are applied by the base.
  virtual void command(const MotionCommand& cmd) = 0;
  // Bump and contact state.
  virtual RobotStatus status() const = 0;
};

}  // namespace coopmap
