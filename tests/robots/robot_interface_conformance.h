// The RobotInterface conformance suite: what every driver (simulated, replayed, real) must do
// for the core to run on it unchanged. The tests are in robot_interface_conformance.cpp;
// compile it into the test executable and instantiate the suite with a factory per driver:
//
//   INSTANTIATE_TEST_SUITE_P(MyDriver, RobotInterfaceConformance,
//                            ::testing::Values(DriverCase{"MyDriver", &makeMyDriver}),
//                            driverCaseName);
//
// The suite only uses the interface, plus the factory's wait() to let time pass on the
// robot's clock (a simulator steps, a replay does nothing, hardware sleeps).
#pragma once

#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <ostream>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/core/mat.hpp>

#include "core/robot/robot_interface.h"

namespace coopmap::test_support {

// A driver ready for the suite.
struct DriverUnderTest {
  std::shared_ptr<void> owner;  // keeps alive whatever the driver borrows (a simulator ...)
  RobotInterface* robot = nullptr;
  std::function<void(double)> wait;  // lets that many seconds pass on the robot's clock
};

struct DriverCase {
  std::string name;                       // a test-name suffix: letters, digits, '_'
  std::function<DriverUnderTest()> make;  // a fresh driver per test
  int frames = 4;                         // frames the driver can deliver at least
};

// Names the case in gtest's messages.
inline void PrintTo(const DriverCase& c, std::ostream* os) { *os << c.name; }

inline std::string driverCaseName(const ::testing::TestParamInfo<DriverCase>& info) {
  return info.param.name;
}

class RobotInterfaceConformance : public ::testing::TestWithParam<DriverCase> {
 protected:
  void SetUp() override {
    driver_ = GetParam().make();
    ASSERT_NE(driver_.robot, nullptr) << "the factory made no driver";
    ASSERT_TRUE(driver_.wait) << "the factory gave no wait()";
  }
  RobotInterface& robot() { return *driver_.robot; }

  // The next frame, letting up to `tries` sensing periods pass while the cameras have none.
  std::optional<TrinocularFrame> nextFrame(int tries = 20) {
    for (int i = 0; i < tries; ++i) {
      if (std::optional<TrinocularFrame> f = robot().captureFrame()) return f;
      driver_.wait(0.1);
    }
    return std::nullopt;
  }

  static bool finite(const Pose2& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
  }

  DriverUnderTest driver_;
};

}  // namespace coopmap::test_support
