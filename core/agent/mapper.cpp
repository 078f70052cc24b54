#include "core/agent/mapper.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

namespace coopmap {

Mapper::Mapper(const RobotDescription& robot, const MapLimits& limits, const MapperConfig& config)
    : robot_(robot),
      config_(config),
      matcher_(robot.rig, config.stereo),
      grid_(limits, config.occupancy) {
  config_.radial.validate();
}

void Mapper::setFrame(const Pose2& X_MO) {
  frame_ = X_MO;
  framed_ = true;
}

void Mapper::setTeammates(std::vector<Eigen::Vector2d> positions, double radius) {
  teammates_ = std::move(positions);
  teammate_radius_ = radius;
}

void Mapper::importMap(const std::vector<int16_t>& log_odds, const std::vector<uint8_t>& seen) {
  grid_.assign(log_odds, seen);
}

const RadialMap& Mapper::process(const TrinocularFrame& frame, MotionSegment segment) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  stats_ = matcher_.compute(frame.reference, frame.horizontal, frame.vertical, disparity_);
  const auto t1 = Clock::now();
  TraverseEntry& entry = traverse_.entries.emplace_back();
  entry.segment = segment;
  const Pose2 pose = estimate(frame.odometry);
  last_scan_ = buildRadialMap(disparity_, robot_, config_.radial, frame.stamp, pose);
  entry.scan = last_scan_;
  if (teammate_radius_ > 0.0 && !teammates_.empty()) {
    const Eigen::Vector2d origin = pose * entry.scan.sensor_origin;
    for (RadialReading& r : entry.scan.readings) {
      if (r.kind != RadialKind::kHit) continue;
      const double a = pose.theta + r.bearing;
      const Eigen::Vector2d hit = origin + r.range * Eigen::Vector2d(std::cos(a), std::sin(a));
      for (const Eigen::Vector2d& t : teammates_) {
        if ((hit - t).norm() > teammate_radius_) continue;
        // Free up to where the teammate's disc begins along the ray, unknown beyond.
        const Eigen::Vector2d d(std::cos(a), std::sin(a));
        const Eigen::Vector2d to = t - origin;
        const double along = to.dot(d);
        const double across2 = std::max(0.0, to.squaredNorm() - along * along);
        const double enter =
            along - std::sqrt(std::max(0.0, teammate_radius_ * teammate_radius_ - across2));
        r.range = std::clamp(enter, 0.0, r.range);
        r.kind = r.range > 0.0 ? RadialKind::kBeyond : RadialKind::kNone;
        ++masked_;
        break;
      }
    }
  }
  raw_odometry_.push_back(frame.odometry);
  grid_.insert(last_scan_, pose);
  const auto t2 = Clock::now();
  timing_.stereo_s += std::chrono::duration<double>(t1 - t0).count();
  timing_.mapping_s += std::chrono::duration<double>(t2 - t1).count();
  ++timing_.frames;
  return last_scan_;
}

}  // namespace coopmap
