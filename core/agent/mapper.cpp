#include "core/agent/mapper.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace coopmap {

Mapper::Mapper(const RobotDescription& robot, const MapLimits& limits, const MapperConfig& config)
    : robot_(robot),
      config_(config),
      matcher_(robot.rig, config.stereo),
      grid_(limits, config.occupancy) {
  config_.radial.validate();
  if (config.stereo.window_shift > 0) {  // the looks' own matcher (see process)
    StereoConfig centred = config.stereo;
    centred.window_shift = 0;
    look_matcher_.emplace(robot.rig, centred);
  }
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

const RadialMap& Mapper::process(const TrinocularFrame& frame, MotionSegment segment,
                                 bool home_base_look) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  stats_ = (home_base_look && look_matcher_ ? *look_matcher_ : matcher_)
               .compute(frame.reference, frame.horizontal, frame.vertical, disparity_);
  const auto t1 = Clock::now();
  TraverseEntry& entry = traverse_.entries.emplace_back();
  entry.segment = segment;
  const Pose2 pose = estimate(frame.odometry);
  last_scan_ = buildRadialMap(disparity_, robot_, config_.radial, frame.stamp, pose);
  entry.scan = last_scan_;
  maskTeammates(entry.scan, pose);
  raw_odometry_.push_back(frame.odometry);
  if (!placement_kept_) unmasked_.push_back(last_scan_);
  grid_.insert(last_scan_, pose);
  const auto t2 = Clock::now();
  timing_.stereo_s += std::chrono::duration<double>(t1 - t0).count();
  timing_.mapping_s += std::chrono::duration<double>(t2 - t1).count();
  if (config_.centred_scans) {
    RadialMap centred = last_scan_;
    if (look_matcher_ && !home_base_look) {
      look_matcher_->compute(frame.reference, frame.horizontal, frame.vertical, centred_disparity_);
      centred = buildRadialMap(centred_disparity_, robot_, config_.radial, frame.stamp, pose);
    }
    if (!placement_kept_) unmasked_centred_.push_back(centred);
    maskTeammates(centred, pose);
    centred_.push_back(std::move(centred));
    timing_.stereo_s += std::chrono::duration<double>(Clock::now() - t2).count();
  }
  ++timing_.frames;
  return last_scan_;
}

void Mapper::keepPlacement() {
  placement_kept_ = true;
  unmasked_.clear();
  unmasked_.shrink_to_fit();
  unmasked_centred_.clear();
  unmasked_centred_.shrink_to_fit();
}

void Mapper::relocate(const Pose2& X_MO) {
  if (placement_kept_)
    throw std::logic_error("Mapper::relocate: the placement was kept (keepPlacement)");
  frame_ = X_MO;
  framed_ = true;
  grid_ = OccupancyGrid(grid_.limits(), config_.occupancy);
  for (size_t i = 0; i < traverse_.entries.size(); ++i) {
    const Pose2 pose = X_MO * raw_odometry_[i];
    RadialMap scan = unmasked_[i];
    scan.odometry = pose;
    grid_.insert(scan, pose);
    maskTeammates(scan, pose);
    traverse_.entries[i].scan = std::move(scan);
    if (config_.centred_scans) {
      RadialMap centred = unmasked_centred_[i];
      centred.odometry = pose;
      maskTeammates(centred, pose);
      centred_[i] = std::move(centred);
    }
  }
}

void Mapper::maskLogged(size_t from) {
  for (size_t i = from; i < traverse_.entries.size(); ++i) {
    RadialMap& scan = traverse_.entries[i].scan;
    maskTeammates(scan, scan.odometry);
    if (config_.centred_scans) maskTeammates(centred_[i], centred_[i].odometry);
  }
}

void Mapper::maskTeammates(RadialMap& scan, const Pose2& pose) {
  if (teammate_radius_ > 0.0 && !teammates_.empty()) {
    const Eigen::Vector2d origin = pose * scan.sensor_origin;
    for (RadialReading& r : scan.readings) {
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
        r.floor_edge = false;
        ++masked_;
        break;
      }
    }
  }
}

}  // namespace coopmap
