// The rFLEX driver against the emulated controller over a pseudo-terminal: odometry, motion,
// segments, bumpers, and serial faults. Timeouts are for liveness only.
#include "robots/rflex/rflex_robot.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>

#include "robots/rflex/rflex_emulator.h"
#include "tests/robots/rflex_fixture.h"

namespace coopmap {
namespace {

using testing::EmulatedRflexRobot;
using testing::eventually;
using testing::testRflexConfig;

void sleepFor(double s) { std::this_thread::sleep_for(std::chrono::duration<double>(s)); }

// Waits until the emulated base stands still and the driver's odometry has caught up with it.
void settle(EmulatedRflexRobot& r) {
  ASSERT_TRUE(eventually([&] {
    return std::abs(r.emulator().linearVelocity()) < 1e-9 &&
           std::abs(r.emulator().angularVelocity()) < 1e-9;
  }));
  // A few odometry reports taken at rest, counted, not timed.
  const uint64_t reports = r.driver().stats().odometry_reports;
  ASSERT_TRUE(eventually([&] { return r.driver().stats().odometry_reports >= reports + 3; }));
}

void expectOdometryMatches(EmulatedRflexRobot& r, double tol_m, double tol_rad) {
  const Pose2 truth = r.emulator().pose();
  const Pose2 odo = r.odometry();
  EXPECT_NEAR(odo.x, truth.x, tol_m);
  EXPECT_NEAR(odo.y, truth.y, tol_m);
  EXPECT_NEAR(wrapAngle(odo.theta - truth.theta), 0.0, tol_rad);
}

TEST(RflexRobotTest, OpensAsksForReportsAndReleasesTheBrake) {
  EmulatedRflexRobot r;
  // The emulator takes the driver's commands on its own thread: the brake's release may land
  // a moment after the driver has opened (the sanitizer build saw it still on).
  EXPECT_TRUE(eventually([&] { return !r.emulator().counters().brake_on; }));
  const RflexEmulatorCounters c = r.emulator().counters();
  EXPECT_EQ(c.report_period_us, 20000u);
  EXPECT_FALSE(c.brake_on);
  EXPECT_GE(r.driver().stats().odometry_reports, 2u);
  EXPECT_FALSE(r.driver().fault());
  EXPECT_FALSE(r.captureFrame());  // a base has no cameras
  const Pose2 p = r.odometry();
  EXPECT_EQ(p.x, 0.0);
  EXPECT_EQ(p.theta, 0.0);
}

TEST(RflexRobotTest, VelocityCommandMovesTheRobotAndOdometryFollows) {
  EmulatedRflexRobot r;
  r.command({0.3, 0.4});
  ASSERT_TRUE(eventually([&] { return r.emulator().pose().x > 0.1; }));
  r.command(MotionCommand::stop());
  settle(r);
  const Pose2 truth = r.emulator().pose();
  EXPECT_GT(truth.theta, 0.08);  // it turned left while driving
  EXPECT_GT(truth.y, 0.003);
  expectOdometryMatches(r, 0.01, 0.005);
  EXPECT_EQ(r.emulator().counters().decoder.bad_checksums, 0u);
  EXPECT_FALSE(r.driver().fault());
}

TEST(RflexRobotTest, ClampsVelocityToTheDescriptionsLimits) {
  EmulatedRflexRobot r;
  r.command({5.0, -9.0});
  const RobotDescription& d = r.description();
  // Each axis is its own rFLEX packet, taken by the emulator's thread one after the other:
  // wait for both (the sanitizer build once read the rotation before its packet landed).
  ASSERT_TRUE(eventually(
      [&] { return r.emulator().targetLinear() > 0.0 && r.emulator().targetAngular() < 0.0; }));
  EXPECT_NEAR(r.emulator().targetLinear(), d.max_linear_speed, 1e-4);
  EXPECT_NEAR(r.emulator().targetAngular(), -d.max_angular_speed, 1e-4);
  r.command(MotionCommand::stop());
  ASSERT_TRUE(eventually([&] { return r.emulator().targetLinear() == 0.0; }));
}

TEST(RflexRobotTest, TurnSegmentTurnsTheAskedAngle) {
  EmulatedRflexRobot r;
  r.command(MotionCommand::turn(-0.6));
  EXPECT_TRUE(r.status().segment_active);
  ASSERT_TRUE(eventually([&] { return !r.status().segment_active; }));
  settle(r);
  const Pose2 truth = r.emulator().pose();
  EXPECT_NEAR(truth.theta, -0.6, 0.02);
  EXPECT_NEAR(truth.translation().norm(), 0.0, 1e-6);  // in place
  expectOdometryMatches(r, 0.005, 0.005);
}

TEST(RflexRobotTest, StraightSegmentDrivesTheAskedDistance) {
  RflexEmulatorConfig e;
  e.start = Pose2(1.0, 2.0, 0.7);  // the odometry frame starts wherever the robot is
  EmulatedRflexRobot r({}, e);
  r.command(MotionCommand::straight(0.15));
  ASSERT_TRUE(eventually([&] { return !r.status().segment_active; }));
  settle(r);
  const Pose2 truth = r.emulator().pose();
  EXPECT_NEAR((truth.translation() - e.start.translation()).norm(), 0.15, 0.01);
  EXPECT_NEAR(truth.theta, 0.7, 0.005);
  EXPECT_NEAR(r.odometry().x, 0.15, 0.01);
  EXPECT_NEAR(r.odometry().y, 0.0, 0.005);
}

TEST(RflexRobotTest, OdometrySurvivesEncoderWrapAround) {
  RflexEmulatorConfig e;
  e.encoder_offset = 0x7FFFFFFFu - 5000u;  // both counters cross INT32_MAX within 6 cm / 0.07 rad
  EmulatedRflexRobot r({}, e);
  r.command({0.4, 0.5});
  ASSERT_TRUE(eventually([&] { return r.emulator().pose().x > 0.08; }));
  r.command(MotionCommand::stop());
  settle(r);
  EXPECT_LT(r.driver().stats().translation_ticks, 0);  // the counter wrapped
  expectOdometryMatches(r, 0.01, 0.005);
}

TEST(RflexRobotTest, ReportsBumps) {
  EmulatedRflexRobot r;
  EXPECT_FALSE(r.status().bumped);
  r.emulator().setBumper(true);
  ASSERT_TRUE(eventually([&] { return r.status().bumped; }));
  EXPECT_EQ(r.status().contact_events, 1);
  r.emulator().setBumper(false);
  ASSERT_TRUE(eventually([&] { return !r.status().bumped; }));
  r.emulator().setBumper(true);
  ASSERT_TRUE(eventually([&] { return r.status().bumped; }));
  EXPECT_EQ(r.status().contact_events, 2);
}

TEST(RflexRobotTest, SkipsGarbageBytesBetweenPackets) {
  EmulatedRflexRobot r;
  r.emulator().setGarbage(true);
  r.command({0.3, -0.3});
  ASSERT_TRUE(eventually([&] { return r.emulator().pose().x > 0.1; }));
  r.command(MotionCommand::stop());
  settle(r);
  const RflexStats s = r.driver().stats();
  EXPECT_GT(s.decoder.garbage_bytes, 100u);
  EXPECT_EQ(s.decoder.bad_checksums, 0u);
  EXPECT_FALSE(r.driver().fault());
  expectOdometryMatches(r, 0.01, 0.005);
}

TEST(RflexRobotTest, DropsAndCountsCorruptChecksums) {
  EmulatedRflexRobot r;
  const uint64_t before = r.driver().stats().odometry_reports;
  r.emulator().corruptNext(3);
  ASSERT_TRUE(eventually([&] { return r.driver().stats().decoder.bad_checksums == 3; }));
  ASSERT_TRUE(eventually([&] { return r.driver().stats().odometry_reports > before + 4; }));
  EXPECT_FALSE(r.driver().fault());
  EXPECT_EQ(r.emulator().counters().corrupt_packets_sent, 3u);
}

TEST(RflexRobotTest, SilentControllerTripsTheWatchdogAndStops) {
  RflexConfig c = testRflexConfig("");
  c.watchdog_timeout = 0.4;
  EmulatedRflexRobot r({}, {}, c);
  r.command({0.3, 0.0});
  ASSERT_TRUE(eventually([&] { return r.emulator().linearVelocity() > 0.2; }));
  r.emulator().setSilent(true);
  ASSERT_TRUE(eventually([&] { return r.driver().fault().has_value(); }));
  const std::string fault = *r.driver().fault();
  EXPECT_NE(fault.find("rflex " + r.emulator().device()), std::string::npos) << fault;
  EXPECT_NE(fault.find("no odometry report"), std::string::npos) << fault;
  EXPECT_NE(fault.find("watchdog"), std::string::npos) << fault;
  EXPECT_NE(fault.find("stop sent"), std::string::npos) << fault;
  // The stop reached the base, and the latched fault refuses new motion.
  ASSERT_TRUE(eventually([&] { return r.emulator().targetLinear() == 0.0; }));
  ASSERT_TRUE(eventually([&] { return r.emulator().linearVelocity() == 0.0; }));
  const uint64_t commands = r.emulator().counters().axis_commands;
  r.command({0.5, 0.0});
  sleepFor(0.1);
  EXPECT_EQ(r.emulator().targetLinear(), 0.0);
  EXPECT_EQ(r.emulator().counters().axis_commands, commands);
}

TEST(RflexRobotTest, HangUpGivesAClearErrorAndNoCrash) {
  EmulatedRflexRobot r;
  r.command({0.2, 0.0});
  r.emulator().hangUp();
  ASSERT_TRUE(eventually([&] { return r.driver().fault().has_value(); }));
  const std::string fault = *r.driver().fault();
  EXPECT_NE(fault.find("hung up"), std::string::npos) << fault;
  EXPECT_NE(fault.find("no stop could be sent"), std::string::npos) << fault;
  r.command({0.3, 0.0});  // ignored, and harmless
  EXPECT_FALSE(r.status().segment_active);
  (void)r.odometry();
}

TEST(RflexRobotTest, NoAnswerFromTheControllerIsAClearError) {
  RflexEmulator e;
  e.setSilent(true);
  RflexConfig c = testRflexConfig(e.device());
  c.startup_timeout = 0.3;
  try {
    RflexRobot robot(c, RobotDescription{});
    FAIL() << "opened a silent controller";
  } catch (const RflexError& err) {
    const std::string m = err.what();
    EXPECT_NE(m.find("no odometry report from the rFLEX controller within 0.3 s"),
              std::string::npos)
        << m;
    EXPECT_NE(m.find("baud rate"), std::string::npos) << m;
  }
}

TEST(RflexRobotTest, MissingDeviceIsAClearError) {
  RflexConfig c = testRflexConfig("/nonexistent/ttyRFLEX");
  try {
    RflexRobot robot(c, RobotDescription{});
    FAIL() << "opened a missing device";
  } catch (const RflexError& err) {
    EXPECT_NE(std::string(err.what()).find("/nonexistent/ttyRFLEX: cannot open"), std::string::npos)
        << err.what();
  }
}

TEST(RflexRobotTest, ConfigErrorsNameTheField) {
  RflexConfig c = testRflexConfig("/dev/null");
  c.baud = 12345;
  try {
    c.validate();
    FAIL() << "accepted baud 12345";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("field 'baud'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("12345"), std::string::npos) << e.what();
  }
  c.baud = 115200;
  c.watchdog_timeout = 0.01;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

TEST(RflexRobotTest, MotionDisabledNeverMovesTheBase) {
  RflexEmulator e;
  RflexConfig c = testRflexConfig(e.device());
  c.enable_motion = false;
  {
    RflexRobot robot(c, RobotDescription{});
    robot.command({0.5, 0.5});
    robot.command(MotionCommand::straight(1.0));
    // Long enough for the commands to have gone out if they were going to: counted in
    // reports received, not timed.
    const uint64_t reports = robot.stats().odometry_reports;
    ASSERT_TRUE(eventually([&] { return robot.stats().odometry_reports >= reports + 5; }));
    EXPECT_FALSE(robot.status().segment_active);
  }
  const RflexEmulatorCounters counters = e.counters();
  EXPECT_EQ(counters.axis_commands, 0u);
  EXPECT_TRUE(counters.brake_on);
  EXPECT_EQ(e.pose().x, 0.0);
}

TEST(RflexRobotTest, ClosingStopsTheBaseAndSetsTheBrake) {
  RflexEmulator e;
  {
    RflexRobot robot(testRflexConfig(e.device()), RobotDescription{});
    robot.command({0.3, 0.0});
    ASSERT_TRUE(eventually([&] { return e.targetLinear() > 0.0; }));
  }
  // The last packets may still be in the pseudo-terminal when the driver is gone.
  EXPECT_TRUE(eventually([&] { return e.counters().brake_on; }));
  EXPECT_EQ(e.targetLinear(), 0.0);
  EXPECT_EQ(e.counters().report_period_us, 0u);
}

}  // namespace
}  // namespace coopmap
