// Bullet physics against what must happen: velocity commands move the robot through its
// contact with the floor, walls stop it and are counted, runs repeat bit for bit, and
// odometry drifts the way its model says.
#include "sim/physics/physics_world.h"

#include <cmath>
#include <utility>

#include <gtest/gtest.h>

#include "core/agent/route_follower.h"
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

namespace coopmap::sim {
namespace {

// Error-free encoder odometry after 2 s of full acceleration from rest, and the truth.
std::pair<double, double> launch(double patch_mu) {
  World w = openWorld(false);
  if (patch_mu > 0) w.surfaces.push_back({"wet", {-1, -1}, {5, 1}, patch_mu});
  PhysicsWorld p(w, 1.0 / 200.0);
  const int r = p.addRobot(RobotDescription{}, {}, DriveConfig{});
  OdometryModel odo(OdometryConfig{}, {}, 1);
  p.command(r, {0.9, 0.0});
  for (int i = 0; i < 400; ++i) {
    p.step();
    odo.integrate(p.wheelVelocity(r), p.truePose(r), p.stepSize());
  }
  return {odo.pose().x, p.truePose(r).x};
}

TEST(SurfaceTest, WheelsSlipOnALowFrictionPatchAndOdometryOvercounts) {
  const auto [odo_dry, true_dry] = launch(0.0);
  EXPECT_NEAR(odo_dry, true_dry, 0.005);  // grip: the encoders see the body's motion
  const auto [odo_wet, true_wet] = launch(0.05);
  // mu 0.05 allows 0.49 m/s^2 against the base's 1 m/s^2 profile: the body lags and the
  // spinning wheels count distance it never made.
  EXPECT_LT(true_wet, true_dry - 0.2);
  EXPECT_GT(odo_wet, true_wet + 0.2);
}

// From rest to 0.4 m/s on a patch of mu 0.05 (0.49 m/s^2 of grip), driven 3 s: the
// encoders' odometry over-count (m). Commands at 20 Hz, as a mission sends them, raised by
// limitSpeedUp at `accel` m/s^2 (0: straight to 0.4, the base's 1 m/s^2 profile doing the
// rest).
double overcountOnTiles(double accel) {
  World w = openWorld(false);
  w.surfaces.push_back({"tiles", {-1, -1}, {5, 1}, 0.05});
  PhysicsWorld p(w, 1.0 / 200.0);
  const int r = p.addRobot(RobotDescription{}, {}, DriveConfig{});
  OdometryModel odo(OdometryConfig{}, {}, 1);
  double sent = 0.0;
  for (int i = 0; i < 600; ++i) {
    if (i % 10 == 0) {
      const MotionCommand cmd = limitSpeedUp({0.4, 0.0}, sent, accel, 0.05);
      sent = cmd.linear;
      p.command(r, cmd);
    }
    p.step();
    odo.integrate(p.wheelVelocity(r), p.truePose(r), p.stepSize());
  }
  return odo.pose().x - p.truePose(r).x;
}

TEST(SurfaceTest, SpeedingUpGentlyKeepsTheGripThatAStartAtFullAccelerationLoses) {
  EXPECT_GT(overcountOnTiles(0.0), 0.03);             // the wheels spin as it starts: 8.7 cm
  EXPECT_LT(std::abs(overcountOnTiles(0.3)), 0.001);  // they grip all the way
  // Near the grip's 0.49 m/s^2 the steps between commands spin them a little: 2 mm at 0.4.
}

TEST(SurfaceTest, SurfacesLoadFromTheWorldFile) {
  const World w = parseWorld(R"(name: s
textures: {carpet: {type: noise}}
floor: {min: [0, 0], max: [4, 4], texture: carpet}
walls: []
surfaces:
  - {name: wet, min: [1, 1], max: [2, 2], traction_mu: 0.1}
home_base:
  corners: [{position: [3, 3], heading_deg: 0}, {position: [3, 3.8], heading_deg: 0}]
  texture: carpet
robots:
  - name: r
    model: )" + std::string(COOPMAP_SOURCE_DIR) +
                                 R"(/robots/b14/b14.yaml
    start: {position: [0.5, 0.5]}
)",
                             "w.yaml");
  ASSERT_EQ(w.surfaces.size(), 1u);
  EXPECT_TRUE(w.surfaces[0].contains({1.5, 1.5}));
  EXPECT_DOUBLE_EQ(w.surfaces[0].traction_mu, 0.1);
}

}  // namespace
}  // namespace coopmap::sim
