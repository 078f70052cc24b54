// The RobotInterface conformance tests (see robot_interface_conformance.h); the
// instantiations per driver live in the drivers' tests.
#include "tests/robots/robot_interface_conformance.h"

#include <cmath>
#include <optional>
#include <vector>

namespace coopmap::test_support {

TEST_P(RobotInterfaceConformance, DescriptionIsValid) {
  const RobotDescription& d = robot().description();
  EXPECT_FALSE(d.model.empty());
  EXPECT_GT(d.body_radius, 0.0);
  EXPECT_GT(d.body_height, 0.0);
  EXPECT_GE(d.swept_height, d.body_height);
  EXPECT_GT(d.max_linear_speed, 0.0);
  EXPECT_GT(d.max_angular_speed, 0.0);
  EXPECT_GT(d.max_linear_accel, 0.0);
  EXPECT_GT(d.max_angular_accel, 0.0);
  const CameraIntrinsics& k = d.rig.intrinsics;
  EXPECT_GT(k.width, 0);
  EXPECT_GT(k.height, 0);
  EXPECT_GT(k.fx, 0.0);
  EXPECT_GT(k.fy, 0.0);
  EXPECT_TRUE(k.cx >= 0.0 && k.cx <= k.width - 1) << "cx " << k.cx;
  EXPECT_TRUE(k.cy >= 0.0 && k.cy <= k.height - 1) << "cy " << k.cy;
  EXPECT_GT(d.rig.referenceBaseline(), 0.0);
  EXPECT_TRUE(d.rig.vertical_offset.allFinite());
  EXPECT_GT(d.rig.vertical_offset.norm(), 0.0);
  EXPECT_TRUE(d.rig.mount_position.allFinite());
  // Valid for the robot's lifetime: the same object, unchanged, after the robot ran.
  const RobotDescription* before = &d;
  const double radius = d.body_radius;
  robot().command(MotionCommand::stop());
  driver_.wait(0.2);
  nextFrame();
  EXPECT_EQ(&robot().description(), before);
  EXPECT_EQ(robot().description().body_radius, radius);
}

TEST_P(RobotInterfaceConformance, ClockNeverGoesBack) {
  double last = robot().now();
  EXPECT_TRUE(std::isfinite(last));
  for (int i = 0; i < 2 * GetParam().frames; ++i) {
    if (i % 2 == 0) {
      nextFrame();
    } else {
      driver_.wait(0.05);
    }
    const double t = robot().now();
    EXPECT_GE(t, last) << "step " << i;
    last = t;
  }
}

TEST_P(RobotInterfaceConformance, FramesHaveTheRigSizeAndIncreasingStamps) {
  const CameraIntrinsics& k = robot().description().rig.intrinsics;
  std::optional<double> last_stamp;
  for (int i = 0; i < GetParam().frames; ++i) {
    const std::optional<TrinocularFrame> f = nextFrame();
    ASSERT_TRUE(f.has_value()) << "no frame " << i;
    for (const cv::Mat* img : {&f->reference, &f->horizontal, &f->vertical}) {
      EXPECT_EQ(img->type(), CV_8UC1) << "frame " << i;
      EXPECT_EQ(img->cols, k.width) << "frame " << i;
      EXPECT_EQ(img->rows, k.height) << "frame " << i;
    }
    EXPECT_TRUE(std::isfinite(f->stamp));
    EXPECT_LE(f->stamp, robot().now() + 1e-9) << "a frame from the future, frame " << i;
    EXPECT_TRUE(finite(f->odometry)) << "frame " << i;
    if (last_stamp) {
      EXPECT_GT(f->stamp, *last_stamp) << "frame " << i;
    }
    last_stamp = f->stamp;
    driver_.wait(0.1);
  }
}

// A frame's odometry is where the robot was when it was taken: on the way from where the robot
// was before the capture to where it is after it (a driver that pairs a frame with the pose of
// another moment puts it off that way).
TEST_P(RobotInterfaceConformance, FramesCarryTheOdometryOfTheirMoment) {
  robot().command({0.2, 0.0});
  driver_.wait(0.3);
  for (int i = 0; i < GetParam().frames; ++i) {
    const Pose2 before = robot().odometry();
    const std::optional<TrinocularFrame> f = robot().captureFrame();
    const Pose2 after = robot().odometry();
    if (!f) {
      driver_.wait(0.1);
      continue;
    }
    const Eigen::Vector2d b = before.translation(), a = after.translation(),
                          at = f->odometry.translation();
    EXPECT_LE((at - b).norm() + (a - at).norm(), (a - b).norm() + 0.005)
        << "frame " << i << " at (" << at.x() << ", " << at.y() << "), the robot went from ("
        << b.x() << ", " << b.y() << ") to (" << a.x() << ", " << a.y() << ")";
    driver_.wait(0.1);
  }
  robot().command(MotionCommand::stop());
}

TEST_P(RobotInterfaceConformance, OdometryIsFinite) {
  for (int i = 0; i < GetParam().frames; ++i) {
    const Pose2 p = robot().odometry();
    EXPECT_TRUE(finite(p)) << "step " << i << ": " << p.x << " " << p.y << " " << p.theta;
    EXPECT_LE(std::abs(p.theta), M_PI + 1e-9) << "heading not wrapped, step " << i;
    nextFrame();
    driver_.wait(0.1);
  }
}

TEST_P(RobotInterfaceConformance, AcceptsEveryKindOfCommand) {
  const std::vector<MotionCommand> commands = {{0.1, 0.0},
                                               {0.0, 0.2},
                                               MotionCommand::turn(0.1),
                                               MotionCommand::straight(0.05),
                                               MotionCommand::stop()};
  for (const MotionCommand& c : commands) {
    EXPECT_NO_THROW(robot().command(c));
    driver_.wait(0.1);
    EXPECT_TRUE(finite(robot().odometry()));
  }
}

TEST_P(RobotInterfaceConformance, StatusIsSane) {
  int contacts = robot().status().contact_events;
  EXPECT_GE(contacts, 0);
  for (int i = 0; i < GetParam().frames; ++i) {
    nextFrame();
    driver_.wait(0.1);
    const RobotStatus s = robot().status();
    EXPECT_GE(s.contact_events, contacts) << "contacts are counted since start, step " << i;
    EXPECT_TRUE(!s.bumped || s.contact_events > 0) << "bumped without a contact, step " << i;
    contacts = s.contact_events;
  }
}

}  // namespace coopmap::test_support
