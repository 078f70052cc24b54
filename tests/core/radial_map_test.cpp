// Radial maps from synthetic disparity images whose geometry is known exactly.
#include "core/perception/radial_map.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/stereo/trinocular_matcher.h"
#include "tests/core/box_scene.h"

namespace coopmap {
namespace {

RobotDescription robot() {
  RobotDescription r;  // defaults: 160x120, f = 80 px, b = 0.1 m, camera 0.9 m high
  r.rig.intrinsics = CameraIntrinsics::fromFov(160, 120, M_PI / 2);
  return r;
}

// Disparity of a level camera looking at a wall at depth z (m) with a floor below:
// pixels above the floor/wall junction see the wall; below it the floor.
cv::Mat wallAndFloor(const RobotDescription& r, double z, double wall_height) {
  const CameraIntrinsics& k = r.rig.intrinsics;
  const double fb = k.fx * r.rig.referenceBaseline(), h = r.rig.mount_position.z();
  cv::Mat d(k.height, k.width, CV_32F, cv::Scalar(kInvalidDisparity));
  for (int v = 0; v < k.height; ++v)
    for (int u = 0; u < k.width; ++u) {
      const double ray_down = (v - k.cy) / k.fy;  // Y/Z
      const double height_at_wall = h - ray_down * z;
      if (height_at_wall >= 0.0 && height_at_wall <= wall_height) {
        d.at<float>(v, u) = static_cast<float>(fb / z);
      } else if (ray_down > 0.0 && height_at_wall < 0.0) {
        d.at<float>(v, u) = static_cast<float>(fb * ray_down / h);  // floor at depth h / ray_down
      }
    }
  return d;
}

TEST(RadialMapTest, RangesMatchWallAndFloorIsIgnored) {
  const RobotDescription r = robot();
  const double z = 2.0;
  const RadialMap m = buildRadialMap(wallAndFloor(r, z, 2.5), r, RadialMapConfig{}, 1.5, Pose2());
  ASSERT_EQ(m.readings.size(), 160u);
  EXPECT_DOUBLE_EQ(m.stamp, 1.5);
  EXPECT_EQ(m.sensor_origin, Eigen::Vector2d(0.10, 0.0));
  for (size_t u = 0; u < m.readings.size(); ++u) {
    const RadialReading& rd = m.readings[u];
    ASSERT_EQ(rd.kind, RadialKind::kHit) << u;
    EXPECT_NEAR(rd.range, z / std::cos(rd.bearing), 1e-4) << u;
    EXPECT_NEAR(rd.sigma, z * z / 8.0 * 0.12 / std::cos(rd.bearing), 1e-6);
  }
  // Column 0 looks 45 degrees to the left (positive bearing), the last one to the right.
  EXPECT_NEAR(m.readings.front().bearing, std::atan(79.5 / 80.0), 1e-9);
  EXPECT_NEAR(m.readings.back().bearing, -std::atan(79.5 / 80.0), 1e-9);
}

TEST(RadialMapTest, ObstacleAboveTheRobotIsIgnored) {
  RobotDescription r = robot();
  // A "wall" seen only between 1.2 m and 2.5 m: a shelf above the robot's swept height.
  cv::Mat d = wallAndFloor(r, 2.0, 2.5);
  const CameraIntrinsics& k = r.rig.intrinsics;
  for (int v = 0; v < k.height; ++v) {
    const double height = 0.9 - (v - k.cy) / k.fy * 2.0;
    if (height < 1.2)
      for (int u = 0; u < k.width; ++u)
        if (d.at<float>(v, u) == 4.0f) d.at<float>(v, u) = kInvalidDisparity;
  }
  const RadialMap m = buildRadialMap(d, r, RadialMapConfig{}, 0.0, Pose2());
  for (const RadialReading& rd : m.readings) EXPECT_NE(rd.kind, RadialKind::kHit);
}

// A textureless wall: its own pixels never match, only the floor in front of it does. Near
// enough that open floor would still be matched beyond it, the floor's end is the wall.
TEST(RadialMapTest, WhereTheFloorEndsNearAnUnmatchableWallStands) {
  const RobotDescription r = robot();
  for (const double z : {1.3, 1.45, 1.8}) {
    cv::Mat d = wallAndFloor(r, z, 2.5);
    const CameraIntrinsics& k = r.rig.intrinsics;
    for (int v = 0; v < k.height; ++v)
      for (int u = 0; u < k.width; ++u)  // the wall: nothing matched
        if (std::abs(d.at<float>(v, u) - 8.0 / z) < 1e-4f) d.at<float>(v, u) = kInvalidDisparity;
    RadialMapConfig on, off;
    on.floor_edge_depth = 1.5;
    const RadialMap m = buildRadialMap(d, r, on, 0.0, Pose2());
    const RadialMap without = buildRadialMap(d, r, off, 0.0, Pose2());
    for (size_t u = 0; u < m.readings.size(); u += 10) {
      const RadialReading& rd = m.readings[u];
      EXPECT_EQ(without.readings[u].kind, RadialKind::kNone);
      if (z > 1.5) {  // could be where open floor stops being matched: nothing known
        EXPECT_EQ(rd.kind, RadialKind::kNone) << z;
        continue;
      }
      ASSERT_EQ(rd.kind, RadialKind::kHit) << "wall at " << z << " m, column " << u;
      // Within three image rows of floor, on the near side: the floor's end falls between
      // rows, and the median of the last five floor rows is two rows nearer than the last.
      const double row = z * z / (r.rig.intrinsics.fy * 0.9) / std::cos(rd.bearing);
      EXPECT_LE(rd.range, z / std::cos(rd.bearing) + 0.01) << "wall at " << z << " m";
      EXPECT_GE(rd.range, z / std::cos(rd.bearing) - 3.0 * row) << "wall at " << z << " m";
    }
  }
}

TEST(RadialMapTest, FarWallCountsAsBeyondRange) {
  const RobotDescription r = robot();
  const RadialMap m = buildRadialMap(wallAndFloor(r, 6.0, 2.5), r, RadialMapConfig{}, 0.0, Pose2());
  for (const RadialReading& rd : m.readings) {
    EXPECT_EQ(rd.kind, RadialKind::kBeyond);
    EXPECT_DOUBLE_EQ(rd.range, 4.0);
  }
}

TEST(RadialMapTest, UnsupportedSinglePixelIsNotAReturn) {
  const RobotDescription r = robot();
  cv::Mat d(120, 160, CV_32F, cv::Scalar(kInvalidDisparity));
  d.at<float>(40, 80) = 10.0f;  // one stray match at 0.8 m
  const RadialMap m = buildRadialMap(d, r, RadialMapConfig{}, 0.0, Pose2());
  EXPECT_EQ(m.readings[80].kind, RadialKind::kNone);
}

TEST(RadialMapTest, ScatteredFarMismatchesAreNotAViewBeyondRange) {
  // A textureless wall 3 m away: no disparity on it but scattered mismatches far beyond
  // range (column 80: two disagreeing, column 81: two alike). With beyond_support 3 (the
  // building's) only column 82, whose far view three pixels agree on, is free to the range:
  // a stray far match in front of the building's plaster wall had cleared the wall's whole
  // length behind it.
  const RobotDescription r = robot();
  cv::Mat d(120, 160, CV_32F, cv::Scalar(kInvalidDisparity));
  // (Rows 60-62 look just below the horizon: 0.5-0.85 m up at 9 m, within the swept height.)
  d.at<float>(60, 80) = 0.9f;
  d.at<float>(62, 80) = 1.8f;
  d.at<float>(60, 81) = 0.9f;
  d.at<float>(62, 81) = 0.9f;
  for (int v = 60; v < 63; ++v) d.at<float>(v, 82) = 1.0f + 0.1f * (v - 60);
  RadialMapConfig three;
  three.beyond_support = 3;
  const RadialMap m = buildRadialMap(d, r, three, 0.0, Pose2());
  EXPECT_EQ(m.readings[80].kind, RadialKind::kNone);
  EXPECT_EQ(m.readings[81].kind, RadialKind::kNone);
  EXPECT_EQ(m.readings[82].kind, RadialKind::kBeyond);
  // The paper's rule (the default): any one far pixel.
  const RadialMap any = buildRadialMap(d, r, RadialMapConfig{}, 0.0, Pose2());
  for (int u = 80; u < 83; ++u) EXPECT_EQ(any.readings[u].kind, RadialKind::kBeyond) << u;
}

TEST(RadialMapTest, SpikeBetweenAgreeingNeighboursIsRemoved) {
  const RobotDescription r = robot();
  cv::Mat d = wallAndFloor(r, 3.0, 2.5);
  for (int v = 50; v < 70; ++v) d.at<float>(v, 60) = 12.0f;  // a mismatch "spike" at 0.67 m
  const RadialMap m = buildRadialMap(d, r, RadialMapConfig{}, 0.0, Pose2());
  EXPECT_EQ(m.readings[60].kind, RadialKind::kNone);
  EXPECT_EQ(m.readings[59].kind, RadialKind::kHit);
  EXPECT_EQ(m.readings[61].kind, RadialKind::kHit);
  // A real obstacle spanning several columns stays.
  for (int u = 90; u < 96; ++u)
    for (int v = 50; v < 70; ++v) d.at<float>(v, u) = 12.0f;
  const RadialMap m2 = buildRadialMap(d, r, RadialMapConfig{}, 0.0, Pose2());
  for (int u = 91; u < 95; ++u) {
    ASSERT_EQ(m2.readings[u].kind, RadialKind::kHit);
    EXPECT_NEAR(m2.readings[u].range * std::cos(m2.readings[u].bearing), 8.0 / 12.0, 1e-4);
  }
}

// A spike that was a hit where the floor's view ends is no hit, and no floor's end, once
// removed.
TEST(RadialMapTest, ARemovedSpikeIsNoFloorEdge) {
  RadialMap m;
  for (int i = 0; i < 3; ++i) {
    RadialReading r;
    r.kind = RadialKind::kHit;
    r.range = i == 1 ? 0.5 : 2.0;
    r.floor_edge = i == 1;
    m.readings.push_back(r);
  }
  EXPECT_EQ(removeSpikes(m, 0.3), 1);
  EXPECT_EQ(m.readings[1].kind, RadialKind::kNone);
  EXPECT_FALSE(m.readings[1].floor_edge);
}

// Stereo to radial map: a textured box 1 m away (disparity 8) in front of a weakly textured
// background 8 m away (beyond range). Centred SAD windows give the background beside the
// box's vertical edges the box's disparity over the whole band, and the radial map then
// reports the box up to window / 2 columns too wide on each side: "phantom" obstacles
// beside furniture. Shiftable windows (window_shift 2) leave at most window / 2 -
// window_shift of them.
TEST(RadialMapTest, StereoDoesNotWidenAnObstacleIntoTheBackground) {
  const RobotDescription r = robot();
  const test::BoxScene scene;  // box columns 60..99, rows 30..89 (0.53 .. 1.27 m high)
  const test::BoxViews v = test::renderBoxScene(scene);
  auto radial = [&](int window_shift) {
    StereoConfig stereo;
    stereo.window_shift = window_shift;
    cv::Mat disparity;
    TrinocularMatcher(r.rig, stereo).compute(v.ref, v.hor, v.ver, disparity);
    return buildRadialMap(disparity, r, RadialMapConfig{}, 0.0, Pose2());
  };
  // Hits in the columns k px left and right of the box.
  auto hitsBeside = [&](const RadialMap& m, int k) {
    int hits = 0;
    for (int u : {scene.box.x - k, scene.box.x + scene.box.width - 1 + k})
      hits += m.readings[u].kind == RadialKind::kHit;
    return hits;
  };
  const StereoConfig defaults;
  const int half = defaults.window / 2, shift = 2;
  const RadialMap centred = radial(0), shiftable = radial(shift);
  int old_phantoms = 0, new_phantoms = 0;
  for (int k = 1; k <= half; ++k) {
    old_phantoms += hitsBeside(centred, k);
    new_phantoms += hitsBeside(shiftable, k);
    if (k > half - shift) {
      EXPECT_EQ(hitsBeside(shiftable, k), 0) << k;
    }
  }
  EXPECT_GE(old_phantoms, 4);  // the old rule's phantom columns
  EXPECT_LE(new_phantoms, 2 * (half - shift));
  // The box is still seen in every one of its columns, at its range.
  for (int u = scene.box.x; u < scene.box.x + scene.box.width; ++u) {
    const RadialReading& rd = shiftable.readings[u];
    ASSERT_EQ(rd.kind, RadialKind::kHit) << u;
    EXPECT_NEAR(rd.range * std::cos(rd.bearing), 1.0, 0.05) << u;
  }
}

}  // namespace
}  // namespace coopmap
