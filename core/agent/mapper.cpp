#include "core/agent/mapper.h"

#include <chrono>

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
  entry.scan = buildRadialMap(disparity_, robot_, config_.radial, frame.stamp, pose);
  raw_odometry_.push_back(frame.odometry);
  grid_.insert(entry.scan, pose);
  const auto t2 = Clock::now();
  timing_.stereo_s += std::chrono::duration<double>(t1 - t0).count();
  timing_.mapping_s += std::chrono::duration<double>(t2 - t1).count();
  ++timing_.frames;
  return entry.scan;
}

}  // namespace coopmap
