#include "robots/carmen/carmen_log_robot.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace coopmap {
namespace {

RobotDescription laserRobotDescription() {
  RobotDescription d;  // a generic wheeled base carrying a planar laser (no cameras used)
  d.model = "carmen_log";
  d.body_radius = 0.25;
  d.body_height = 0.5;
  d.swept_height = 0.6;
  d.max_linear_speed = 1.0;
  d.max_angular_speed = 1.5;
  return d;
}

}  // namespace

void CarmenRobotConfig::validate() const {
  auto bad = [](const std::string& f, const std::string& e, double v) {
    throw std::invalid_argument("carmen robot config: field '" + f + "': expected " + e + ", got " +
                                std::to_string(v));
  };
  if (laser < 0 || laser > 4)
    bad("laser", "an integer in [0, 4] (0: the lowest in the log)", laser);
  if (!(range_sigma >= 0.0) || !std::isfinite(range_sigma))
    bad("range_sigma", "a number >= 0", range_sigma);
}

CarmenLogRobot::CarmenLogRobot(CarmenLog log, const CarmenRobotConfig& config)
    : log_(std::move(log)), description_(laserRobotDescription()) {
  config.validate();
  const std::string& file = log_.file;
  if (log_.lasers.empty())
    throw CarmenLogError(file +
                         ": no laser scans (FLASER, RLASER, RAWLASER1-4 or ROBOTLASER1-2 lines)");
  laser_ = config.laser;
  if (laser_ == 0) {
    laser_ = 4;
    for (const CarmenLaser& l : log_.lasers) laser_ = std::min(laser_, l.laser);
  }
  std::vector<size_t> chosen;
  for (size_t i = 0; i < log_.lasers.size(); ++i)
    if (log_.lasers[i].laser == laser_) chosen.push_back(i);
  if (chosen.empty()) throw CarmenLogError(file + ": no scans of laser " + std::to_string(laser_));

  // The odometry track: ODOM, or the poses the laser messages carry.
  for (const CarmenOdometry& o : log_.odometry) track_.push_back({o.stamp, o.pose});
  if (track_.empty()) {
    for (size_t i : chosen) {
      const CarmenLaser& l = log_.lasers[i];
      if (!l.robot_pose)
        throw CarmenLogError(file + ":" + std::to_string(l.line) + ": " + l.message +
                             " has no odometry and the log has no ODOM lines");
      track_.push_back({l.stamp, *l.robot_pose});
    }
  }

  // The laser mount X_RL, unless each message gives its own (ROBOTLASER).
  Pose2 mount;
  if (config.mount) {
    mount = *config.mount;
  } else if (laser_ <= 2) {
    const std::string side = laser_ == 1 ? "front" : "rear";
    mount.x = log_.numericParam("robot_" + side + "laser_offset").value_or(0.0);
    mount.y = log_.numericParam("robot_" + side + "laser_side_offset").value_or(0.0);
    mount.theta = log_.numericParam("robot_" + side + "laser_angular_offset").value_or(0.0) +
                  (laser_ == 2 ? M_PI : 0.0);
  }

  scans_.reserve(chosen.size());
  for (size_t i : chosen) {
    CarmenLaser& l = log_.lasers[i];
    RangeScan s;
    s.stamp = l.stamp;
    s.odometry = l.robot_pose ? *l.robot_pose : odometryAt(l.stamp);
    Pose2 X_RL = mount;
    if (!config.mount && l.robot_pose && l.laser_pose && l.message.starts_with("ROBOTLASER"))
      X_RL = l.robot_pose->inverse() * *l.laser_pose;
    s.sensor_origin = X_RL.translation();
    s.start_angle = wrapAngle(X_RL.theta + l.start_angle);
    s.angular_resolution = l.angular_resolution;
    s.max_range = l.max_range;
    s.range_sigma = config.range_sigma > 0.0 ? config.range_sigma : std::max(0.01, l.accuracy);
    s.ranges = std::move(l.ranges);  // the scan owns them now; the log keeps the rest
    scans_.push_back(std::move(s));
  }
  now_ = scans_.front().stamp;
  if (!track_.empty()) now_ = std::min(now_, track_.front().stamp);
}

std::optional<RangeScan> CarmenLogRobot::captureScan() {
  if (next_ >= scans_.size()) return std::nullopt;
  const RangeScan& s = scans_[next_++];
  now_ = std::max(now_, s.stamp);
  return s;
}

void CarmenLogRobot::advanceTo(double stamp) { now_ = std::max(now_, stamp); }

Pose2 CarmenLogRobot::odometryAt(double stamp) const {
  if (track_.empty()) return {};
  const auto after = std::upper_bound(track_.begin(), track_.end(), stamp,
                                      [](double t, const StampedPose2& p) { return t < p.stamp; });
  if (after == track_.begin()) return track_.front().pose;
  if (after == track_.end()) return track_.back().pose;
  const StampedPose2& a = *(after - 1);
  const StampedPose2& b = *after;
  const double span = b.stamp - a.stamp;
  const double w = span > 0.0 ? (stamp - a.stamp) / span : 1.0;
  return {a.pose.x + w * (b.pose.x - a.pose.x), a.pose.y + w * (b.pose.y - a.pose.y),
          wrapAngle(a.pose.theta + w * wrapAngle(b.pose.theta - a.pose.theta))};
}

std::vector<StampedPose2> CarmenLogRobot::groundTruth() const {
  std::vector<StampedPose2> out;
  out.reserve(log_.truth.size());
  for (const CarmenTruePose& t : log_.truth) out.push_back({t.stamp, t.truth});
  return out;
}

}  // namespace coopmap
