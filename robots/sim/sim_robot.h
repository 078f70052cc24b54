// The simulated B-14: the robot interface over one robot of a Simulator.
#pragma once

#include "core/robot/robot_interface.h"
#include "sim/simulator.h"

namespace coopmap {

class SimRobot final : public RobotInterface {
 public:
  // `sim` is borrowed and must outlive this driver.
  SimRobot(sim::Simulator& sim, int index) : sim_(sim), index_(index) {}

  const RobotDescription& description() const override { return sim_.description(index_); }
  double now() const override { return sim_.time(); }
  std::optional<TrinocularFrame> captureFrame() override { return sim_.capture(index_); }
  Pose2 odometry() const override { return sim_.odometry(index_); }
  void command(const MotionCommand& cmd) override { sim_.command(index_, cmd); }
  RobotStatus status() const override { return sim_.status(index_); }

  int index() const { return index_; }

 private:
  sim::Simulator& sim_;
  int index_;
};

}  // namespace coopmap
