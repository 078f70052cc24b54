#include "sim/sensors/odometry.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace coopmap::sim {

void OdometryConfig::validate() const {
  auto bad = [](const std::string& f, const std::string& e, double v) {
    throw std::invalid_argument("odometry: field '" + f + "': expected " + e + ", got " +
                                std::to_string(v));
  };
  if (!(std::abs(scale_error) < 0.5)) bad("scale_error", "a fraction in (-0.5, 0.5)", scale_error);
  if (!(std::abs(turn_scale_error) < 0.5))
    bad("turn_scale_error", "a fraction in (-0.5, 0.5)", turn_scale_error);
  if (!(std::abs(heading_drift) < 0.5)) bad("heading_drift", "rad/m in (-0.5, 0.5)", heading_drift);
  if (!(linear_noise >= 0.0 && linear_noise < 1.0))
    bad("linear_noise", "a number in [0, 1)", linear_noise);
  if (!(heading_noise >= 0.0 && heading_noise < 1.0))
    bad("heading_noise", "a number in [0, 1)", heading_noise);
  if (!(angular_noise >= 0.0 && angular_noise < 1.0))
    bad("angular_noise", "a number in [0, 1)", angular_noise);
}

OdometryModel::OdometryModel(const OdometryConfig& config, const Pose2& true_start, uint64_t seed)
    : config_(config), start_inverse_(true_start.inverse()), rng_(seed) {
  config_.validate();
}

void OdometryModel::integrate(const BodyVelocity& v, const Pose2& true_pose, double dt) {
  if (config_.perfect) {
    pose_ = start_inverse_ * true_pose;
    return;
  }
  // Random errors grow with the distance driven and the angle turned, not with time.
  const double ds_true = v.forward * dt, dtheta_true = v.yaw_rate * dt;
  double ds = ds_true * (1.0 + config_.scale_error);
  if (config_.linear_noise > 0.0)
    ds += config_.linear_noise * std::sqrt(std::abs(ds_true)) * normal_(rng_);
  double dtheta =
      dtheta_true * (1.0 + config_.turn_scale_error) + config_.heading_drift * std::abs(ds_true);
  if (config_.angular_noise > 0.0)
    dtheta += config_.angular_noise * std::sqrt(std::abs(dtheta_true)) * normal_(rng_);
  if (config_.heading_noise > 0.0)
    dtheta += config_.heading_noise * std::sqrt(std::abs(ds_true)) * normal_(rng_);
  // Midpoint integration of the unicycle model.
  const double mid = pose_.theta + 0.5 * dtheta;
  pose_.x += ds * std::cos(mid);
  pose_.y += ds * std::sin(mid);
  pose_.theta = wrapAngle(pose_.theta + dtheta);
}

}  // namespace coopmap::sim
