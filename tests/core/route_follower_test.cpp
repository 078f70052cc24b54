// The route follower driving an ideal unicycle: it must visit every waypoint, turning in
// place before driving straight, and spin where asked.
#include "core/agent/route_follower.h"

#include <cmath>

#include <gtest/gtest.h>

namespace coopmap {
namespace {

struct Trace {
  Pose2 final_pose;
  double max_turn_while_driving = 0.0;  // |omega| while v > 0.05
  double total_rotation = 0.0;
  int steps = 0;
};

Trace drive(RouteFollower& f, Pose2 pose, double dt = 0.05, int max_steps = 20000) {
  Trace t;
  for (; t.steps < max_steps && !f.done(); ++t.steps) {
    const MotionCommand c = f.update(pose);
    if (c.linear > 0.05)
      t.max_turn_while_driving = std::max(t.max_turn_while_driving, std::abs(c.angular));
    t.total_rotation += std::abs(c.angular) * dt;
    pose.x += c.linear * dt * std::cos(pose.theta);
    pose.y += c.linear * dt * std::sin(pose.theta);
    pose.theta = wrapAngle(pose.theta + c.angular * dt);
  }
  t.final_pose = pose;
  return t;
}

TEST(RouteFollowerTest, VisitsWaypointsInOrder) {
  RouteFollower f({{{2.0, 0.0}, false}, {{2.0, 2.0}, false}, {{0.0, 0.0}, false}}, RouteConfig{});
  const Trace t = drive(f, Pose2(0, 0, 0));
  ASSERT_TRUE(f.done());
  EXPECT_NEAR(t.final_pose.x, 0.0, 0.06);
  EXPECT_NEAR(t.final_pose.y, 0.0, 0.06);
  // Turns happen in place: while driving, only small heading corrections.
  EXPECT_LT(t.max_turn_while_driving, 0.2);
  // Two turns of 90 and 135 degrees, approximately.
  EXPECT_NEAR(t.total_rotation, M_PI / 2 + 3 * M_PI / 4, 0.2);
}

TEST(RouteFollowerTest, SpinTurnsAFullCircle) {
  RouteFollower f({{{0.0, 0.0}, true}}, RouteConfig{});
  const Trace t = drive(f, Pose2(0, 0, 0.3));
  ASSERT_TRUE(f.done());
  EXPECT_NEAR(t.total_rotation, 2 * M_PI, 0.1);
}

TEST(RouteFollowerTest, WaitsThenSpins) {
  Waypoint home;
  home.spin = true;
  home.wait = 3.0;
  RouteFollower f({home}, RouteConfig{});
  // Standing still until t = 3 s, whatever the pose.
  for (double t = 0.0; t < 2.95; t += 0.05) {
    const MotionCommand c = f.update(Pose2(), t);
    ASSERT_EQ(c.linear, 0.0) << "t " << t;
    ASSERT_EQ(c.angular, 0.0) << "t " << t;
  }
  EXPECT_FALSE(f.done());
  EXPECT_GT(f.update(Pose2(), 3.0).angular, 0.0);  // then the spin begins
}

TEST(RouteFollowerTest, EmptyRouteStops) {
  RouteFollower f({}, RouteConfig{});
  EXPECT_TRUE(f.done());
  const MotionCommand c = f.update(Pose2());
  EXPECT_EQ(c.linear, 0.0);
  EXPECT_EQ(c.angular, 0.0);
}

}  // namespace
}  // namespace coopmap
