// The rFLEX driver against an emulated controller on a pseudo-terminal, as a robot interface
// that owns both: for the driver's tests and for suites run over every robot interface.
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <thread>

#include "core/robot/robot_interface.h"
#include "robots/rflex/rflex_emulator.h"
#include "robots/rflex/rflex_robot.h"

namespace coopmap::testing {

// Driver settings for tests: fast reports, and timeouts generous enough for a loaded machine
// (the watchdog must not trip on a busy core).
inline RflexConfig testRflexConfig(const std::string& device) {
  RflexConfig c;
  c.device = device;
  c.report_period = 0.02;
  c.watchdog_timeout = 1.0;
  c.startup_timeout = 5.0;
  c.write_timeout = 1.0;
  c.control_period = 0.01;
  return c;
}

// Polls `pred` every 5 ms until it holds or `timeout_s` passes; returns whether it held.
template <class Pred>
bool eventually(Pred pred, double timeout_s = 10.0) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < deadline) {
    if (pred()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return pred();
}

// An emulated controller and the driver on it. The driver is destroyed first.
class EmulatedRflexRobot final : public RobotInterface {
 public:
  explicit EmulatedRflexRobot(const RobotDescription& description = {},
                              const RflexEmulatorConfig& emulator_config = {},
                              std::optional<RflexConfig> config = std::nullopt)
      : emulator_(std::make_unique<RflexEmulator>(emulator_config)) {
    RflexConfig c = config ? *config : testRflexConfig(emulator_->device());
    c.device = emulator_->device();
    robot_ = std::make_unique<RflexRobot>(c, description);
  }
  ~EmulatedRflexRobot() override {
    robot_.reset();
    emulator_.reset();
  }

  const RobotDescription& description() const override { return robot_->description(); }
  double now() const override { return robot_->now(); }
  std::optional<TrinocularFrame> captureFrame() override { return robot_->captureFrame(); }
  Pose2 odometry() const override { return robot_->odometry(); }
  void command(const MotionCommand& cmd) override { robot_->command(cmd); }
  RobotStatus status() const override { return robot_->status(); }

  RflexRobot& driver() { return *robot_; }
  RflexEmulator& emulator() { return *emulator_; }

 private:
  std::unique_ptr<RflexEmulator> emulator_;
  std::unique_ptr<RflexRobot> robot_;
};

// A B-14 base (the default description: the B-14's body and limits) driven over rFLEX by an
// emulated controller, behind the robot interface.
inline std::unique_ptr<RobotInterface> makeEmulatedRflexRobot(
    const RobotDescription& description = {}) {
  return std::make_unique<EmulatedRflexRobot>(description);
}

}  // namespace coopmap::testing
