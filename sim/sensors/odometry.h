// Wheel odometry: integrates what the encoders measure (the base's body velocity with
// systematic and random errors), not the true pose.
#pragma once

#include <cstdint>
#include <random>

#include "core/geometry/pose2.h"
#include "sim/physics/physics_world.h"

namespace coopmap::sim {

struct OdometryConfig {
  bool perfect = false;           // report the true motion since the start (tests and baselines)
  double scale_error = 0.0;       // fraction: measured distance = (1 + e) * true
  double turn_scale_error = 0.0;  // fraction: measured rotation = (1 + e) * true
  double heading_drift = 0.0;     // rad per metre driven (wheel misalignment)
  double linear_noise = 0.0;      // fraction of speed, 1-sigma per sqrt(s)
  double angular_noise = 0.0;     // rad/s per sqrt(s) while turning, 1-sigma
  double heading_noise = 0.0;     // rad per sqrt(m) driven, 1-sigma random walk

  void validate() const;  // throws std::invalid_argument naming the field
};

class OdometryModel {
 public:
  // `true_start`: the robot's true pose at the start (world frame). The odometry starts at
  // the origin, as encoders do.
  OdometryModel(const OdometryConfig& config, const Pose2& true_start, uint64_t seed);
  // Integrates one physics step of the measured body velocity.
  void integrate(const BodyVelocity& measured, const Pose2& true_pose, double dt);
  const Pose2& pose() const { return pose_; }  // X_OR, odometry frame

 private:
  OdometryConfig config_;
  Pose2 start_inverse_;  // X_OW: the world in the odometry frame
  Pose2 pose_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

}  // namespace coopmap::sim
