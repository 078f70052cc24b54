#include "core/agent/mapper.h"

namespace coopmap {

Mapper::Mapper(const RobotDescription& robot, const MapLimits& limits, const MapperConfig& config)
    : robot_(robot),
      config_(config),
      matcher_(robot.rig, config.stereo),
      grid_(limits, config.occupancy) {
  config_.radial.validate();
}

const RadialMap& Mapper::process(const TrinocularFrame& frame) {
  stats_ = matcher_.compute(frame.reference, frame.horizontal, frame.vertical, disparity_);
  traverse_.push_back(
      buildRadialMap(disparity_, robot_, config_.radial, frame.stamp, frame.odometry));
  grid_.insert(traverse_.back(), frame.odometry);
  return traverse_.back();
}

}  // namespace coopmap
