// `coopmap remap --oracle`: which part of each pose comes from the ground truth.
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "sim/runner/remap.h"

namespace coopmap {
namespace {

// The robot faces +y at the truth; the pose is 0.3 m off across that (x) and 0.5 m along it.
const Pose2 kTruth(1.0, 2.0, M_PI / 2);
const Pose2 kPose(1.3, 2.5, M_PI / 2 + 0.1);

void expectPose(const Pose2& p, double x, double y, double theta) {
  EXPECT_NEAR(p.x, x, 1e-12);
  EXPECT_NEAR(p.y, y, 1e-12);
  EXPECT_NEAR(p.theta, theta, 1e-12);
}

TEST(RemapOracleTest, AlongTakesTheErrorAlongTheTrueHeadingOutAndKeepsTheRest) {
  expectPose(oraclePose(kPose, kTruth, "along"), 1.3, 2.0, kPose.theta);
}

TEST(RemapOracleTest, AcrossTakesTheErrorAcrossTheTrueHeadingOutAndKeepsTheRest) {
  expectPose(oraclePose(kPose, kTruth, "across"), 1.0, 2.5, kPose.theta);
}

TEST(RemapOracleTest, AlongAndAcrossSplitTheErrorAtAnyHeading) {
  const Pose2 truth(-3.0, 4.0, 2.4);
  const Pose2 pose(-2.7, 3.6, 2.3);
  const Pose2 a = oraclePose(pose, truth, "along");
  const Pose2 b = oraclePose(pose, truth, "across");
  // What each leaves are the two parts of the error: they sum to it, at right angles, and
  // the part `along` leaves is across the heading.
  const Eigen::Vector2d left_a = a.translation() - truth.translation();
  const Eigen::Vector2d left_b = b.translation() - truth.translation();
  EXPECT_NEAR((left_a + left_b - (pose.translation() - truth.translation())).norm(), 0.0, 1e-12);
  EXPECT_NEAR(left_a.dot(left_b), 0.0, 1e-12);
  EXPECT_NEAR(left_a.dot(Eigen::Vector2d(std::cos(truth.theta), std::sin(truth.theta))), 0.0,
              1e-12);
  EXPECT_GT(left_a.norm(), 0.05);
  EXPECT_GT(left_b.norm(), 0.05);
}

TEST(RemapOracleTest, PositionAndHeadingTakeTheirPartWhole) {
  expectPose(oraclePose(kPose, kTruth, "position"), 1.0, 2.0, kPose.theta);
  expectPose(oraclePose(kPose, kTruth, "heading"), 1.3, 2.5, kTruth.theta);
  expectPose(oraclePose(kPose, kTruth, ""), 1.3, 2.5, kPose.theta);
}

TEST(RemapOracleTest, AnUnknownPartIsNamedInTheError) {
  try {
    oraclePose(kPose, kTruth, "speed");
    FAIL() << "no error for an unknown oracle";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'speed'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("along or across"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace coopmap
