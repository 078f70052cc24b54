// Reading CARMEN logs: every message type the reader knows, and exact messages for bad lines.
#include "core/io/carmen_log.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

namespace coopmap {
namespace {

constexpr double kDeg = M_PI / 180.0;

std::string ranges(int n, const char* value) {
  std::string s;
  for (int i = 0; i < n; ++i) s += std::string(" ") + value;
  return s;
}

TEST(CarmenLogTest, ReadsEveryKnownMessage) {
  const std::string text =
      "# CARMEN Logfile\n"
      "# file format is one message per line\n"
      "\n"
      "PARAM robot_frontlaser_offset 0.12 nohost 0.0\n"
      "SYNC tag1 0.5 host 0.5\n"
      "ODOM 1.0 2.0 0.5 0.3 0.1 0.0 10.0 host 10.01\r\n"
      "ODOM\t1.1 2.0 0.5 0.3 0.1 0.0 10.1 host 10.11\n"
      "FLASER 181" +
      ranges(181, "2.5") +
      " 5 6 0.7 1.0 2.0 0.5 10.05 host 10.06\n"
      "RAWLASER2 0 -2.0 4.0 0.01 30.0 0.001 0 3 1.0 2.0 3.0 2 7 8 10.2 host 10.21\n"
      "ROBOTLASER1 0 -1.5 3.0 1.5 8.0 0.01 0 3 1 2 3 0 1.2 2.0 0.5 1.0 2.0 0.5 0.3 0.1 0.5 "
      "0.3 0.0 10.3 host 10.31\n"
      "TRUEPOS 1.01 2.02 0.51 1.0 2.0 0.5 10.0 host 10.0\n"
      "NMEAGGA 1 2 3 4 N 5 E 1 8 1.0 100 0 0 0 0 11.0 host 11.0\n";
  const CarmenLog log = parseCarmenLog(text, "t.log");
  EXPECT_EQ(log.file, "t.log");
  EXPECT_EQ(log.lines, 12);

  ASSERT_EQ(log.odometry.size(), 2u);
  EXPECT_DOUBLE_EQ(log.odometry[0].pose.x, 1.0);
  EXPECT_DOUBLE_EQ(log.odometry[0].pose.theta, 0.5);
  EXPECT_DOUBLE_EQ(log.odometry[0].tv, 0.3);
  EXPECT_DOUBLE_EQ(log.odometry[0].stamp, 10.0);
  EXPECT_EQ(log.odometry[0].line, 6);
  EXPECT_DOUBLE_EQ(log.odometry[1].pose.x, 1.1);  // tab-separated

  ASSERT_EQ(log.lasers.size(), 3u);
  const CarmenLaser& f = log.lasers[0];
  EXPECT_EQ(f.message, "FLASER");
  EXPECT_EQ(f.laser, 1);
  ASSERT_EQ(f.ranges.size(), 181u);
  EXPECT_FLOAT_EQ(f.ranges[180], 2.5f);
  EXPECT_NEAR(f.start_angle, -90.0 * kDeg, 1e-12);  // CARMEN's SICK LMS convention
  EXPECT_NEAR(f.angular_resolution, 1.0 * kDeg, 1e-12);
  EXPECT_NEAR(f.field_of_view, 180.0 * kDeg, 1e-9);
  EXPECT_DOUBLE_EQ(f.max_range, 80.0);
  ASSERT_TRUE(f.laser_pose && f.robot_pose);
  EXPECT_DOUBLE_EQ(f.laser_pose->x, 5.0);
  EXPECT_DOUBLE_EQ(f.robot_pose->theta, 0.5);
  EXPECT_DOUBLE_EQ(f.stamp, 10.05);

  const CarmenLaser& r = log.lasers[1];
  EXPECT_EQ(r.message, "RAWLASER2");
  EXPECT_EQ(r.laser, 2);
  EXPECT_DOUBLE_EQ(r.start_angle, -2.0);
  EXPECT_DOUBLE_EQ(r.field_of_view, 4.0);
  EXPECT_DOUBLE_EQ(r.angular_resolution, 0.01);
  EXPECT_DOUBLE_EQ(r.max_range, 30.0);
  EXPECT_DOUBLE_EQ(r.accuracy, 0.001);
  EXPECT_EQ(r.ranges, (std::vector<float>{1.0f, 2.0f, 3.0f}));
  EXPECT_FALSE(r.robot_pose.has_value());
  EXPECT_DOUBLE_EQ(r.stamp, 10.2);

  const CarmenLaser& b = log.lasers[2];
  EXPECT_EQ(b.message, "ROBOTLASER1");
  EXPECT_EQ(b.laser, 1);
  ASSERT_TRUE(b.laser_pose && b.robot_pose);
  EXPECT_DOUBLE_EQ(b.laser_pose->x, 1.2);
  EXPECT_DOUBLE_EQ(b.robot_pose->x, 1.0);
  EXPECT_DOUBLE_EQ(b.stamp, 10.3);

  ASSERT_EQ(log.truth.size(), 1u);
  EXPECT_DOUBLE_EQ(log.truth[0].truth.y, 2.02);
  EXPECT_DOUBLE_EQ(log.truth[0].odometry.y, 2.0);

  EXPECT_EQ(log.numericParam("robot_frontlaser_offset"), 0.12);
  EXPECT_EQ(log.numericParam("robot_rearlaser_offset"), std::nullopt);
  EXPECT_EQ(log.skipped_messages.at("SYNC"), 1);
  EXPECT_EQ(log.skipped_messages.at("NMEAGGA"), 1);
}

TEST(CarmenLogTest, OldLaserMessagesGuessTheirAnglesFromTheBeamCount) {
  const CarmenLog log = parseCarmenLog("FLASER 361" + ranges(361, "1") +
                                           " 0 0 0 0 0 0 1.0 h 1.0\n"
                                           "RLASER 401" +
                                           ranges(401, "1") + " 0 0 0 0 0 0 1.0 h 1.0\n",
                                       "t.log");
  ASSERT_EQ(log.lasers.size(), 2u);
  EXPECT_NEAR(log.lasers[0].angular_resolution, 0.5 * kDeg, 1e-12);
  EXPECT_NEAR(log.lasers[0].start_angle, -90.0 * kDeg, 1e-12);
  EXPECT_EQ(log.lasers[1].laser, 2);
  EXPECT_NEAR(log.lasers[1].angular_resolution, 0.25 * kDeg, 1e-12);
  EXPECT_NEAR(log.lasers[1].start_angle, -50.0 * kDeg, 1e-12);  // the 100 degree mode
}

std::string errorOf(const std::string& text) {
  try {
    parseCarmenLog(text, "bad.log");
  } catch (const CarmenLogError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(CarmenLogTest, BadLinesNameFileLineMessageAndField) {
  const std::string odom_ok = "ODOM 1 2 0.5 0 0 0 10.0 host 10.0\n";
  EXPECT_EQ(errorOf(odom_ok + "ODOM 1 2 abc 0 0 0 11.0 host 11.0\n"),
            "bad.log:2: ODOM field 'theta': expected a number, got 'abc'");
  EXPECT_EQ(errorOf("# comment\nODOM 1 2 0.5 0 0\n"),
            "bad.log:2: ODOM field 'accel': expected a number, got the end of the line");
  EXPECT_EQ(errorOf("ODOM 1 2 0.5 0 0 0 10.0 host\n"),
            "bad.log:1: ODOM field 'logger_timestamp': expected a number, got the end of the "
            "line");
  EXPECT_EQ(errorOf("ODOM 1 2 0.5 0 0 0 10.0 host 10.0 extra\n"),
            "bad.log:1: ODOM: expected the end of the line after field 'logger_timestamp', got "
            "'extra'");
  EXPECT_EQ(errorOf("ODOM 1 2 nan 0 0 0 10.0 host 10.0\n"),
            "bad.log:1: ODOM field 'theta': expected a finite number, got 'nan'");
  EXPECT_EQ(errorOf(odom_ok + "ODOM 1 2 0.5 0 0 0 9.5 host 11.0\n"),
            "bad.log:2: ODOM field 'ipc_timestamp': expected a time not before the previous "
            "ODOM (10.000000 at line 1), got '9.5'");
}

TEST(CarmenLogTest, BadLaserLinesNameTheField) {
  // Fewer ranges than announced: the pose fields run out first.
  EXPECT_EQ(errorOf("FLASER 5 1 1 1 0 0 0 0 0 0 1.0 h 1.0\n"),
            "bad.log:1: FLASER field 'odom_theta': expected a number, got 'h'");
  EXPECT_EQ(errorOf("FLASER 3 1 x 1 0 0 0 0 0 0 1.0 h 1.0\n"),
            "bad.log:1: FLASER field 'range[1]': expected a number, got 'x'");
  EXPECT_EQ(errorOf("FLASER -3 1 1 1 0 0 0 0 0 0 1.0 h 1.0\n"),
            "bad.log:1: FLASER field 'num_readings': expected an integer in [1, 100000], got "
            "'-3'");
  EXPECT_EQ(errorOf("FLASER 2.5 1 1 0 0 0 0 0 0 1.0 h 1.0\n"),
            "bad.log:1: FLASER field 'num_readings': expected an integer in [1, 100000], got "
            "'2.5'");
  EXPECT_EQ(errorOf("RAWLASER1 0 -1.57 3.14 0 80 0.01 0 2 1 1 0 1.0 h 1.0\n"),
            "bad.log:1: RAWLASER1 field 'angular_resolution': expected a number in (0, "
            "3.141593], got '0'");
  EXPECT_EQ(errorOf("RAWLASER1 0 -1.57 3.14 0.01 80 0.01 0 2 1 1 4 5 5 1.0 h 1.0\n"),
            "bad.log:1: RAWLASER1 field 'remission[3]': expected a number, got 'h'");
  EXPECT_EQ(errorOf("RAWLASER3 0 -1.57 3.14 0.01 80 0.01 0 1 1 0 2.0 h 2.0\n"
                    "RAWLASER1 0 -1.57 3.14 0.01 80 0.01 0 1 1 0 2.0 h 2.0\n"
                    "RAWLASER3 0 -1.57 3.14 0.01 80 0.01 0 1 1 0 1.5 h 2.0\n"),
            "bad.log:3: RAWLASER3 field 'ipc_timestamp': expected a time not before the "
            "previous scan of laser 3 (2.000000 at line 1), got '1.5'");
  EXPECT_EQ(errorOf("ROBOTLASER1 0 -1.5 3.0 1.5 8.0 0.01 0 1 1 0 1 2 0 1 2 0 0 0 0.5 0.3\n"),
            "bad.log:1: ROBOTLASER1 field 'turn_axis': expected a number, got the end of the "
            "line");
  EXPECT_EQ(errorOf("PARAM robot_frontlaser_offset\n"),
            "bad.log:1: PARAM field 'param_value': expected a word, got the end of the line");
}

TEST(CarmenLogTest, FileErrorsNameTheFile) {
  try {
    readCarmenLog("/nonexistent/run.log");
    FAIL() << "no error for a missing file";
  } catch (const CarmenLogError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/run.log: cannot open the log file");
  }
  EXPECT_EQ(errorOf(std::string("\x1f\x8b\x08\x00", 4)),
            "bad.log: a gzip-compressed log: decompress it first (gunzip)");
  const CarmenLog log = parseCarmenLog("PARAM robot_frontlaser_offset zero h 0\n", "p.log");
  try {
    log.numericParam("robot_frontlaser_offset");
    FAIL() << "a non-numeric PARAM was read as a number";
  } catch (const CarmenLogError& e) {
    EXPECT_STREQ(e.what(),
                 "p.log:1: PARAM field 'robot_frontlaser_offset': expected a number, got 'zero'");
  }
}

}  // namespace
}  // namespace coopmap
