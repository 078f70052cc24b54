// Bullet physics against what must happen: velocity commands move the robot through its
// contact with the floor, walls stop it and are counted, runs repeat bit for bit, and
// odometry drifts the way its model says.
#include "sim/physics/physics_world.h"

#include <cmath>

#include <gtest/gtest.h>

#include "sim/sensors/odometry.h"

namespace coopmap::sim {
namespace {

World openWorld(bool with_wall) {
  World w;
  w.floor_min = {-2, -5};
  w.floor_max = {12, 5};
  if (with_wall) {
    WallSpec wall;
    wall.from = {3.0, -2.0};
    wall.to = {3.0, 2.0};
    wall.thickness = 0.1;
    w.walls.push_back(wall);
  }
  return w;
}

struct DriveResult {
  Pose2 pose;
  BodyVelocity velocity;
  int contacts = 0;
  bool touching = false;
};

DriveResult drive(const World& w, const MotionCommand& cmd, double seconds,
                  const Pose2& start = {}) {
  PhysicsWorld p(w, 1.0 / 200.0);
  const int r = p.addRobot(RobotDescription{}, start, DriveConfig{});
  p.command(r, cmd);
  for (int i = 0; i < static_cast<int>(seconds * 200); ++i) p.step();
  return {p.truePose(r), p.bodyVelocity(r), p.contactEvents(r), p.inContact(r)};
}

TEST(PhysicsTest, VelocityCommandMovesTheRobot) {
  const DriveResult r = drive(openWorld(false), {0.4, 0.0}, 3.0);
  // Ramp at 1 m/s^2 to 0.4 m/s (0.4 s, 0.08 m), then cruise: 0.08 + 0.4 * 2.6 = 1.12 m,
  // less a little for the servo's lag.
  EXPECT_NEAR(r.pose.x, 1.12, 0.03);
  EXPECT_NEAR(r.pose.y, 0.0, 1e-3);
  EXPECT_NEAR(r.pose.theta, 0.0, 1e-3);
  EXPECT_NEAR(r.velocity.forward, 0.4, 0.01);
  EXPECT_EQ(r.contacts, 0);
}

TEST(PhysicsTest, TurnsInPlace) {
  const DriveResult r = drive(openWorld(false), {0.0, 1.0}, 2.0);
  EXPECT_NEAR(r.pose.x, 0.0, 1e-3);
  EXPECT_NEAR(r.pose.y, 0.0, 1e-3);
  // Ramp at 3 rad/s^2 to 1 rad/s (1/3 s, 1/6 rad), then 5/3 s: ~1.83 rad.
  EXPECT_NEAR(r.pose.theta, 1.83, 0.05);
}

TEST(PhysicsTest, WallStopsTheRobotAndTheContactIsCounted) {
  const DriveResult r = drive(openWorld(true), {0.5, 0.0}, 10.0);
  // The wall's near face is at x = 2.95; the body (radius 0.178) stops against it.
  EXPECT_NEAR(r.pose.x, 2.95 - 0.178, 0.02);
  EXPECT_TRUE(r.touching);
  EXPECT_EQ(r.contacts, 1);
}

TEST(PhysicsTest, SameInputsGiveBitIdenticalRuns) {
  const DriveResult a = drive(openWorld(true), {0.6, 0.3}, 6.0, Pose2(0, -1, 0.2));
  const DriveResult b = drive(openWorld(true), {0.6, 0.3}, 6.0, Pose2(0, -1, 0.2));
  EXPECT_EQ(a.pose.x, b.pose.x);
  EXPECT_EQ(a.pose.y, b.pose.y);
  EXPECT_EQ(a.pose.theta, b.pose.theta);
}

TEST(OdometryTest, HeadingDriftAccumulatesWithDistance) {
  // 8 m straight with 0.0055 rad/m of drift: about 2.5 degrees, as the paper measured.
  OdometryConfig c;
  c.heading_drift = 0.0055;
  PhysicsWorld p(openWorld(false), 1.0 / 200.0);
  const int r = p.addRobot(RobotDescription{}, {}, DriveConfig{});
  OdometryModel odo(c, {}, 7);
  p.command(r, {0.5, 0.0});
  while (p.truePose(r).x < 8.0) {
    p.step();
    odo.integrate(p.bodyVelocity(r), p.truePose(r), p.stepSize());
  }
  const double err = wrapAngle(odo.pose().theta - p.truePose(r).theta);
  EXPECT_NEAR(err * 180 / M_PI, 2.52, 0.05);
  // Odometry bends left of the true straight path.
  EXPECT_GT(odo.pose().y, 0.1);
}

TEST(OdometryTest, PerfectOdometryIsTheTruth) {
  OdometryConfig c;
  c.perfect = true;
  OdometryModel odo(c, {}, 1);
  odo.integrate({1.0, 0.0, 0.0}, Pose2(1, 2, 3), 0.01);
  EXPECT_EQ(odo.pose().x, 1.0);
  EXPECT_EQ(odo.pose().theta, 3.0);
}

TEST(OdometryTest, NoiseIsSeeded) {
  OdometryConfig c;
  c.linear_noise = 0.05;
  c.angular_noise = 0.05;
  auto run = [&](uint64_t seed) {
    OdometryModel odo(c, {}, seed);
    for (int i = 0; i < 1000; ++i) odo.integrate({0.5, 0.0, 0.3}, {}, 0.005);
    return odo.pose();
  };
  EXPECT_EQ(run(3).x, run(3).x);
  EXPECT_NE(run(3).x, run(4).x);
}

}  // namespace
}  // namespace coopmap::sim
