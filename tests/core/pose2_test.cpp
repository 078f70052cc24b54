#include "core/geometry/pose2.h"

#include <gtest/gtest.h>

namespace coopmap {
namespace {

TEST(Pose2Test, WrapAngleStaysInHalfOpenInterval) {
  EXPECT_NEAR(wrapAngle(3 * M_PI), M_PI, 1e-12);
  EXPECT_NEAR(wrapAngle(-M_PI), M_PI, 1e-12);
  EXPECT_NEAR(wrapAngle(2 * M_PI + 0.1), 0.1, 1e-12);
  EXPECT_NEAR(wrapAngle(-0.1), -0.1, 1e-12);
}

TEST(Pose2Test, ComposeAndInvert) {
  const Pose2 a(1.0, 2.0, M_PI / 2), b(1.0, 0.0, M_PI / 2);
  const Pose2 c = a * b;  // one metre along a's x axis (world +y), then turn again
  EXPECT_NEAR(c.x, 1.0, 1e-12);
  EXPECT_NEAR(c.y, 3.0, 1e-12);
  EXPECT_NEAR(c.theta, M_PI, 1e-12);
  const Pose2 i = a * a.inverse();
  EXPECT_NEAR(i.x, 0.0, 1e-12);
  EXPECT_NEAR(i.y, 0.0, 1e-12);
  EXPECT_NEAR(i.theta, 0.0, 1e-12);
  const Eigen::Vector2d p = a * Eigen::Vector2d(0.0, 1.0);  // a's +y is world -x
  EXPECT_NEAR(p.x(), 0.0, 1e-12);
  EXPECT_NEAR(p.y(), 2.0, 1e-12);
}

}  // namespace
}  // namespace coopmap
