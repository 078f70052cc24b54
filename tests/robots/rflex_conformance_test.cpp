// The RobotInterface conformance suite on the rFLEX driver, against the emulated controller.
// A B-14 base has no cameras, so the case promises no frames (frames = 0): the suite checks
// the description, the clock, odometry, commands and status on the wall clock.
#include <chrono>
#include <memory>
#include <thread>

#include <gtest/gtest.h>

#include "tests/robots/rflex_fixture.h"
#include "tests/robots/robot_interface_conformance.h"

namespace coopmap::test_support {
namespace {

DriverUnderTest makeRflexDriver() {
  std::shared_ptr<RobotInterface> robot = testing::makeEmulatedRflexRobot();
  RobotInterface* raw = robot.get();
  return {robot, raw,
          [](double dt) { std::this_thread::sleep_for(std::chrono::duration<double>(dt)); }};
}

INSTANTIATE_TEST_SUITE_P(Rflex, RobotInterfaceConformance,
                         ::testing::Values(DriverCase{"RflexRobot", &makeRflexDriver, 0}),
                         driverCaseName);

}  // namespace
}  // namespace coopmap::test_support
