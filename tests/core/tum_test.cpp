// TUM trajectories: what coopmap writes reads back to the same poses, and a bad line is
// reported with the file and line.
#include "core/io/tum.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace coopmap {
namespace {

std::string errorOf(const std::string& text) {
  try {
    parseTum(text, "t.tum");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(TumTest, WrittenTrajectoryReadsBack) {
  const std::vector<StampedPose2> written = {
      {0.0, Pose2(1.5, -2.0, 0.3)}, {0.05, Pose2(1.6, -2.0, -3.1)}, {7.25, Pose2(0.0, 4.0, 2.9)}};
  const std::vector<StampedPose2> read = parseTum(formatTum(written, "a robot"), "t.tum");
  ASSERT_EQ(read.size(), written.size());
  for (size_t i = 0; i < read.size(); ++i) {
    EXPECT_NEAR(read[i].stamp, written[i].stamp, 1e-6);
    EXPECT_NEAR(read[i].pose.x, written[i].pose.x, 1e-6);
    EXPECT_NEAR(read[i].pose.y, written[i].pose.y, 1e-6);
    EXPECT_NEAR(wrapAngle(read[i].pose.theta - written[i].pose.theta), 0.0, 1e-8);
  }
}

TEST(TumTest, HeadingIsTheYawOfAnyUnitQuaternion) {
  // A yaw of 90 degrees written by another tool as a negated quaternion.
  const auto read = parseTum("1.0 0 0 0 0 0 -0.7071067811865476 -0.7071067811865476\n", "t.tum");
  ASSERT_EQ(read.size(), 1u);
  EXPECT_NEAR(read[0].pose.theta, M_PI / 2, 1e-9);
}

TEST(TumTest, BadLinesNameTheFileAndLine) {
  EXPECT_EQ(errorOf("# header\n0 1 2 0 0 0 0 1\n0.1 1 2 0 0 0\n"),
            "t.tum:3: expected 8 numbers (timestamp tx ty tz qx qy qz qw), got '0.1 1 2 0 0 0'");
  EXPECT_EQ(
      errorOf("0 1 2 0 0 0 0 1 9\n"),
      "t.tum:1: expected 8 numbers (timestamp tx ty tz qx qy qz qw), got '0 1 2 0 0 0 0 1 9'");
  EXPECT_EQ(errorOf("1 0 0 0 0 0 0 1\n0.5 0 0 0 0 0 0 1\n"),
            "t.tum:2: timestamp 0.500000 is earlier than the one before (1.000000)");
  EXPECT_THROW(readTum("/nonexistent/t.tum"), std::runtime_error);
}

}  // namespace
}  // namespace coopmap
