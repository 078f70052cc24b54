// Planar rigid transforms (SE(2)) following ROS REP-103: x forward, y left, theta CCW.
#pragma once

#include <cmath>

#include <Eigen/Core>

namespace coopmap {

// Wraps an angle in radians to (-pi, pi].
inline double wrapAngle(double a) {
  a = std::fmod(a + M_PI, 2.0 * M_PI);
  if (a <= 0.0) a += 2.0 * M_PI;
  return a - M_PI;
}

// Pose of a frame B in a frame A (X_AB): translation in metres, heading in radians.
struct Pose2 {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;

  Pose2() = default;
  Pose2(double x_, double y_, double theta_) : x(x_), y(y_), theta(theta_) {}

  Eigen::Vector2d translation() const { return {x, y}; }

  // Composition X_AC = X_AB * X_BC.
  Pose2 operator*(const Pose2& b) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * b.x - s * b.y, y + s * b.x + c * b.y, wrapAngle(theta + b.theta)};
  }

  // Maps a point given in frame B into frame A.
  Eigen::Vector2d operator*(const Eigen::Vector2d& p) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * p.x() - s * p.y(), y + s * p.x() + c * p.y()};
  }

  // X_BA from X_AB.
  Pose2 inverse() const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {-c * x - s * y, s * x - c * y, wrapAngle(-theta)};
  }
};

}  // namespace coopmap
