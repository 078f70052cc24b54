// The mapper's two matchers: frames of a look at the home base are matched on centred
// windows, every other frame on the configured ones (shiftable by default); with
// centred_scans every frame's centred match is kept beside the logged one.
#include "core/agent/mapper.h"

#include <cmath>

#include <gtest/gtest.h>

#include "tests/core/box_scene.h"

namespace coopmap {
namespace {

RobotDescription robot() {
  RobotDescription r;  // 160x120, f = 80 px, b = 0.1 m
  r.rig.intrinsics = CameraIntrinsics::fromFov(160, 120, M_PI / 2);
  return r;
}

TrinocularFrame boxFrame() {
  const test::BoxViews v = test::renderBoxScene(test::BoxScene{});
  TrinocularFrame f;
  f.reference = v.ref;
  f.horizontal = v.hor;
  f.vertical = v.ver;
  return f;
}

MapLimits limits() { return MapLimits::covering({-5.0, -5.0}, {5.0, 5.0}, 0.05); }

std::vector<RadialKind> kinds(const RadialMap& m) {
  std::vector<RadialKind> out;
  for (const RadialReading& r : m.readings) out.push_back(r.kind);
  return out;
}

std::vector<double> ranges(const RadialMap& m) {
  std::vector<double> out;
  for (const RadialReading& r : m.readings) out.push_back(r.range);
  return out;
}

// The box scene's vertical edges tell the two matchers apart: centred windows widen the box
// into the background beside it (radial_map_test), shiftable ones much less.
TEST(MapperTest, ALookAtTheHomeBaseIsMatchedOnCentredWindows) {
  const RobotDescription r = robot();
  const TrinocularFrame frame = boxFrame();
  MapperConfig shiftable;
  shiftable.stereo.window_shift = 2;
  MapperConfig centred = shiftable;
  centred.stereo.window_shift = 0;

  Mapper mapper(r, limits(), shiftable), reference(r, limits(), centred);
  const RadialMap driving = mapper.process(frame, MotionSegment::kStraight);
  const RadialMap look = mapper.process(frame, MotionSegment::kTurn, true);
  const RadialMap as_centred = reference.process(frame, MotionSegment::kTurn);

  EXPECT_EQ(kinds(look), kinds(as_centred));
  EXPECT_EQ(ranges(look), ranges(as_centred));
  EXPECT_NE(kinds(driving), kinds(look)) << "the scene no longer tells the matchers apart";
  // Both go into the traverse log, in order, with their segments.
  ASSERT_EQ(mapper.traverse().entries.size(), 2u);
  EXPECT_EQ(mapper.traverse().entries[0].segment, MotionSegment::kStraight);
  EXPECT_EQ(mapper.traverse().entries[1].segment, MotionSegment::kTurn);
}

// The distance scale from stereo is matched on centred windows: each entry's centred scan is
// kept beside it, at the entry's pose, moved with it by relocate.
TEST(MapperTest, KeepsEachFramesCentredScanBesideTheShiftableOne) {
  const RobotDescription r = robot();
  TrinocularFrame frame = boxFrame();
  MapperConfig shiftable;
  ASSERT_GT(shiftable.stereo.window_shift, 0) << "shiftable windows are the default";
  shiftable.centred_scans = true;
  MapperConfig centred = shiftable;
  centred.stereo.window_shift = 0;
  centred.centred_scans = false;

  Mapper mapper(r, limits(), shiftable), reference(r, limits(), centred);
  const RadialMap driving = mapper.process(frame, MotionSegment::kStraight);
  frame.odometry = Pose2(0.5, 0.0, 0.1);
  const RadialMap look = mapper.process(frame, MotionSegment::kTurn, true);
  const RadialMap as_centred = reference.process(frame, MotionSegment::kStraight);

  const std::vector<RadialMap>& kept = mapper.centredScans();
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kinds(kept[0]), kinds(as_centred));
  EXPECT_EQ(ranges(kept[0]), ranges(as_centred));
  EXPECT_NE(kinds(kept[0]), kinds(mapper.traverse().entries[0].scan))
      << "the logged scan is the shiftable windows'";
  EXPECT_EQ(kinds(kept[1]), kinds(look));  // a look is matched on centred windows already
  EXPECT_EQ(kept[1].odometry.x, 0.5);

  const Pose2 X(1.0, -2.0, 0.3);
  mapper.relocate(X);
  for (size_t i = 0; i < kept.size(); ++i) {
    const Pose2 moved = X * mapper.rawOdometry()[i];
    EXPECT_NEAR(kept[i].odometry.x, moved.x, 1e-12);
    EXPECT_NEAR(kept[i].odometry.y, moved.y, 1e-12);
    EXPECT_NEAR(kept[i].odometry.theta, moved.theta, 1e-12);
  }
  EXPECT_TRUE(Mapper(r, limits(), centred).centredScans().empty());
}

}  // namespace
}  // namespace coopmap
