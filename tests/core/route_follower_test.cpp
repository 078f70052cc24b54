// The route follower driving an ideal unicycle: it must visit every waypoint, turning in
// place before driving straight, and spin where asked.
#include "core/agent/route_follower.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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

TEST(RouteFollowerTest, ArrivesWithinTheWaypointsOwnTolerance) {
  Waypoint near;
  near.position = {1.3, 0.4};
  near.arrive_tolerance = 0.01;  // the route's is 5 cm
  RouteFollower f({near}, RouteConfig{});
  const Trace t = drive(f, Pose2(0, 0, 0));
  ASSERT_TRUE(f.done());
  EXPECT_LT(std::hypot(t.final_pose.x - 1.3, t.final_pose.y - 0.4), 0.012);
}

TEST(RouteFollowerTest, FacesTheGivenHeadingThenWaitsThenSpins) {
  Waypoint look;
  look.position = {1.0, 0.0};
  look.face = -2.5;  // rad: behind and to the right of the way it arrives
  look.wait = 2.0;
  look.spin = true;
  RouteFollower f({look}, RouteConfig{});
  Pose2 pose(0, 0, 0);
  double t = 0.0, still_since = -1.0, heading_when_still = 0.0;
  bool spun = false;
  for (int i = 0; i < 20000 && !f.done(); ++i, t += 0.05) {
    const MotionCommand c = f.update(pose, t);
    if (c.linear == 0.0 && c.angular == 0.0 && (pose.translation() - look.position).norm() < 0.06) {
      if (still_since < 0.0) still_since = t, heading_when_still = pose.theta;
    } else if (still_since >= 0.0 && c.angular > 0.0 && c.linear == 0.0) {
      spun = true;
      // The wait came after the turn to the heading, and lasted as asked.
      EXPECT_NEAR(t - still_since, 2.0, 0.06);
      break;
    }
    pose.x += c.linear * 0.05 * std::cos(pose.theta);
    pose.y += c.linear * 0.05 * std::sin(pose.theta);
    pose.theta = wrapAngle(pose.theta + c.angular * 0.05);
  }
  ASSERT_TRUE(spun);
  EXPECT_NEAR(wrapAngle(heading_when_still - -2.5), 0.0, RouteConfig{}.face_tolerance + 0.002);
}

TEST(RouteFollowerTest, SpeedingUpIsLimitedAndSlowingDownIsNot) {
  const MotionCommand go{0.4, 0.2};
  EXPECT_NEAR(limitSpeedUp(go, 0.0, 0.4, 0.05).linear, 0.02, 1e-12);       // from a standstill
  EXPECT_NEAR(limitSpeedUp(go, 0.3, 0.4, 0.05).linear, 0.32, 1e-12);       // on from 0.3 m/s
  EXPECT_DOUBLE_EQ(limitSpeedUp(go, 0.3, 0.4, 0.05).angular, 0.2);         // turning is not
  EXPECT_DOUBLE_EQ(limitSpeedUp(go, 0.39, 0.4, 0.05).linear, 0.4);         // within reach
  EXPECT_DOUBLE_EQ(limitSpeedUp({0.1, 0.0}, 0.4, 0.4, 0.05).linear, 0.1);  // slowing down
  EXPECT_DOUBLE_EQ(limitSpeedUp(MotionCommand::stop(), 0.4, 0.4, 0.05).linear, 0.0);
  EXPECT_NEAR(limitSpeedUp({-0.1, 0.0}, 0.4, 0.4, 0.05).linear, -0.02, 1e-12);  // reversing
  EXPECT_DOUBLE_EQ(limitSpeedUp(go, 0.0, 0.0, 0.05).linear, 0.4);               // off
  EXPECT_EQ(limitSpeedUp(MotionCommand::straight(2.0), 0.0, 0.4, 0.05).amount, 2.0);
}

// A quarter turn in place towards a waypoint on a base that turns no faster than it can
// accelerate (3 rad/s^2) and takes each command a control step late. Returns the steps until
// the first command to drive, and the heading's largest overshoot of the waypoint's bearing.
struct QuarterTurn {
  int steps = 0;
  double overshoot = 0.0;
  double error_when_driving = 0.0;
};
QuarterTurn quarterTurn(const RouteConfig& config) {
  RouteFollower f({{{0.0, 2.0}, false}}, config);
  const double dt = 0.05, max_accel = 3.0, target = M_PI / 2;
  double theta = 0.0, omega = 0.0, pending = 0.0;
  QuarterTurn q;
  for (; q.steps < 2000; ++q.steps) {
    const MotionCommand c = f.update(Pose2(0.0, 0.0, theta));
    if (c.linear > 0.0) break;
    omega += std::clamp(pending - omega, -max_accel * dt, max_accel * dt);
    pending = c.angular;
    theta += omega * dt;
    q.overshoot = std::max(q.overshoot, theta - target);
  }
  q.error_when_driving = std::abs(wrapAngle(target - theta));
  return q;
}

TEST(RouteFollowerTest, ATurnInPlaceSlowsDownAsTheBaseCanStopIt) {
  RouteConfig proportional;
  RouteConfig decelerating;
  decelerating.angular_decel = 1.5;  // half the base's
  const QuarterTurn slow = quarterTurn(proportional);
  const QuarterTurn fast = quarterTurn(decelerating);
  ASSERT_LT(slow.steps, 2000);
  ASSERT_LT(fast.steps, 2000);
  // The proportional law crawls through the last tenths of a radian; the decelerating one
  // holds its rate until the base must brake: a quarter turn half a second sooner.
  EXPECT_LE(fast.steps + 10, slow.steps) << fast.steps << " vs " << slow.steps;
  // ... and still stops on the bearing: within the tolerance, never past it by more.
  EXPECT_LE(fast.error_when_driving, decelerating.heading_tolerance);
  EXPECT_LE(fast.overshoot, decelerating.heading_tolerance);
  RouteConfig bad;
  bad.angular_decel = -1.0;
  EXPECT_THROW(bad.validate(), std::invalid_argument);
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
