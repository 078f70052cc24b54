// Segment commands as the paper's robots moved: the base turns in place by an angle or
// drives straight a distance by its own encoders, then stops.
#include <cmath>

#include <gtest/gtest.h>

#include "robots/robot_model.h"
#include "sim/simulator.h"

namespace coopmap {
namespace {

struct Fixture {
  sim::Simulator sim;
  explicit Fixture(bool perfect) : sim(world(), 3) {
    RobotModel m = loadRobotModel(std::string(COOPMAP_SOURCE_DIR) + "/robots/b14/b14.yaml");
    m.odometry.perfect = perfect;
    sim::RobotSpec spec;
    spec.name = "r";
    sim.addRobot(spec, {m.description, m.drive, m.odometry, {}});
  }
  static sim::World world() {
    sim::World w;
    w.floor_min = {-10, -10};
    w.floor_max = {10, 10};
    sim::TextureSpec t;
    t.name = "carpet";
    w.textures["carpet"] = t;
    w.floor_texture = "carpet";
    return w;
  }
  // Runs until the segment is done (and a second more to settle); false on time out.
  bool run(const MotionCommand& c) {
    sim.command(0, c);
    for (int i = 0; i < 400 && sim.status(0).segment_active; ++i) sim.advance(0.05);
    sim.advance(1.0);
    return !sim.status(0).segment_active;
  }
};

TEST(SegmentTest, TurnsInPlaceByTheAngle) {
  Fixture f(true);
  ASSERT_TRUE(f.run(MotionCommand::turn(M_PI / 2)));
  const Pose2 p = f.sim.truePose(0);
  EXPECT_NEAR(p.theta, M_PI / 2, 1.0 * M_PI / 180);
  EXPECT_NEAR(std::hypot(p.x, p.y), 0.0, 0.005);
  ASSERT_TRUE(f.run(MotionCommand::turn(-M_PI)));
  EXPECT_NEAR(f.sim.truePose(0).theta, -M_PI / 2, 1.0 * M_PI / 180);
}

TEST(SegmentTest, DrivesStraightTheDistance) {
  Fixture f(true);
  ASSERT_TRUE(f.run(MotionCommand::straight(1.5)));
  const Pose2 p = f.sim.truePose(0);
  EXPECT_NEAR(p.x, 1.5, 0.02);
  EXPECT_NEAR(p.y, 0.0, 0.01);
  ASSERT_TRUE(f.run(MotionCommand::straight(-0.5)));
  EXPECT_NEAR(f.sim.truePose(0).x, 1.0, 0.02);
}

TEST(SegmentTest, TheBaseTrustsItsEncoders) {
  // With drifting odometry the segment ends where the encoders say: 8 m straight bends by
  // the preset's heading drift (about 2.5 degrees) in truth while odometry holds heading.
  Fixture f(false);
  ASSERT_TRUE(f.run(MotionCommand::straight(8.0)));
  const Pose2 odo = f.sim.odometry(0), truth = f.sim.truePose(0);
  EXPECT_NEAR(odo.theta, 0.0, 0.5 * M_PI / 180);
  EXPECT_NEAR(std::abs(wrapAngle(truth.theta - odo.theta)) * 180 / M_PI, 2.5, 1.0);
}

}  // namespace
}  // namespace coopmap
