// Tracking against the shared map: radial maps of a room, placed at a drifted estimate,
// pull the estimate back towards the truth; in a part of the world the map does not know,
// or off by more than a step may be, nothing changes. Headings from the walls: the room's
// walls run along the axes, and turn a drifted heading back without any map.
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "core/agent/map_tracker.h"
#include "tests/core/segment_world.h"

namespace coopmap {
namespace {

using test::cameraScan;
using test::Segment;

// A 6 m x 5 m room with a box in it, origin at its south-west corner.
std::vector<Segment> room() {
  return {{{0, 0}, {6, 0}},   {{6, 0}, {6, 5}},       {{6, 5}, {0, 5}},       {{0, 5}, {0, 0}},
          {{3, 2}, {3.8, 2}}, {{3.8, 2}, {3.8, 2.6}}, {{3.8, 2.6}, {3, 2.6}}, {{3, 2.6}, {3, 2}}};
}

OccupancyGrid roomMap() {
  OccupancyGrid map(MapLimits::covering({-0.5, -0.5}, {6.5, 5.5}, 0.05), OccupancyConfig{});
  for (int i = 0; i < 36; ++i)
    for (const Eigen::Vector2d& p : {Eigen::Vector2d(1.5, 1.5), Eigen::Vector2d(4.5, 3.8)}) {
      const Pose2 pose(p.x(), p.y(), i * M_PI / 18.0);
      map.insert(cameraScan(pose, room()), pose);
    }
  return map;
}

const Pose2 kLast(4.5, 1.2, -0.4);  // the latest true pose: facing the south-east corner

// Six scans of a robot driving to kLast, placed at a drifted estimate: a
// rigid error of the estimate's frame that puts the latest pose at kLast * off.
std::vector<RadialMap> drifted(const Pose2& off, const std::vector<Segment>& world) {
  const Pose2 frame_error = kLast * off * kLast.inverse();
  std::vector<RadialMap> out;
  for (int i = 0; i < 6; ++i) {
    const Pose2 truth = kLast * Pose2(-0.1 * (5 - i), 0.0, 0.0);
    RadialMap m = cameraScan(truth, world);
    m.odometry = frame_error * truth;
    out.push_back(m);
  }
  return out;
}

TEST(MapTrackerTest, PullsADriftedEstimateTowardsTheMap) {
  MapTrackerConfig c;
  c.period = 1;
  c.gain = 1.0;
  MapTracker tracker(c);
  EXPECT_FALSE(tracker.update(drifted(Pose2(), room())).has_value()) << "no map yet";
  tracker.setMap(roomMap());
  ASSERT_TRUE(tracker.hasMap());
  const Pose2 off(0.12, -0.08, 0.03);
  const std::vector<RadialMap> scans = drifted(off, room());
  const std::optional<Pose2> correction = tracker.update(scans);
  ASSERT_TRUE(correction.has_value());
  const Pose2 truth = kLast;
  const Pose2 before = scans.back().odometry, after = *correction * before;
  EXPECT_GT(std::hypot(before.x - truth.x, before.y - truth.y), 0.14);
  EXPECT_LT(std::hypot(after.x - truth.x, after.y - truth.y), 0.03);
  EXPECT_LT(std::abs(wrapAngle(after.theta - truth.theta)), 0.01);
  EXPECT_EQ(tracker.accepted(), 1);
}

TEST(MapTrackerTest, DampsEachStepAndAlignsOnlyEveryPeriod) {
  MapTrackerConfig c;
  c.period = 3;
  c.gain = 0.5;
  MapTracker tracker(c);
  tracker.setMap(roomMap());
  const std::vector<RadialMap> scans = drifted(Pose2(0.1, 0.0, 0.0), room());
  EXPECT_FALSE(tracker.update(scans).has_value());
  EXPECT_FALSE(tracker.update(scans).has_value());
  const std::optional<Pose2> correction = tracker.update(scans);
  ASSERT_TRUE(correction.has_value());
  EXPECT_EQ(tracker.aligned(), 1);
  const Pose2 after = *correction * scans.back().odometry;
  EXPECT_NEAR(std::hypot(after.x - kLast.x, after.y - kLast.y), 0.05, 0.015)
      << "half of the 10 cm step";
}

TEST(MapTrackerTest, UnknownTerritoryAndImplausibleStepsChangeNothing) {
  MapTrackerConfig c;
  c.period = 1;
  MapTracker tracker(c);
  tracker.setMap(roomMap());
  // A different room: the map knows nothing of its walls.
  std::vector<Segment> other;
  for (const Segment& s : room()) other.push_back({s.a * 0.6, s.b * 0.6});
  EXPECT_FALSE(tracker.update(drifted(Pose2(), other)).has_value());
  // Off by more than max_step_m: not trusted, even if it aligns.
  EXPECT_FALSE(tracker.update(drifted(Pose2(0.45, 0.0, 0.0), room())).has_value());
  EXPECT_EQ(tracker.accepted(), 0);
}

TEST(MapTrackerTest, BadConfigurationNamesTheField) {
  MapTrackerConfig c;
  c.gain = 0.0;
  try {
    MapTracker t(c);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'gain'"), std::string::npos) << e.what();
  }
}

// The room's walls run along the map's axes: scans placed at an estimate whose heading has
// drifted show them turned, and the walls alone turn the estimate back, about where it is.
TEST(WallHeadingTrackerTest, TurnsADriftedHeadingBackAboutTheRobot) {
  WallHeadingConfig c;
  c.gain = 1.0;
  c.period = 1;
  WallHeadingTracker headings(c);
  for (const double deg : {-2.0, -0.7, 1.5}) {
    const std::vector<RadialMap> scans = drifted(Pose2(0.0, 0.0, deg * M_PI / 180.0), room());
    const Pose2 before = scans.back().odometry;
    const std::optional<Pose2> correction = headings.update(scans);
    ASSERT_TRUE(correction.has_value()) << deg;
    const Pose2 after = *correction * before;
    EXPECT_GT(std::abs(wrapAngle(before.theta - kLast.theta)), 0.6 * M_PI / 180.0) << deg;
    EXPECT_LT(std::abs(wrapAngle(after.theta - kLast.theta)), 0.1 * M_PI / 180.0) << deg;
    EXPECT_LT((after.translation() - before.translation()).norm(), 1e-9) << "turned in place";
  }
  EXPECT_EQ(headings.turned(), 3);
}

TEST(WallHeadingTrackerTest, DampsEachTurnAndFitsOnlyEveryPeriod) {
  WallHeadingConfig c;
  c.gain = 0.5;
  c.period = 3;
  WallHeadingTracker headings(c);
  const std::vector<RadialMap> scans = drifted(Pose2(0.0, 0.0, 0.03), room());
  EXPECT_FALSE(headings.update(scans).has_value());
  EXPECT_FALSE(headings.update(scans).has_value());
  const std::optional<Pose2> correction = headings.update(scans);
  ASSERT_TRUE(correction.has_value());
  EXPECT_EQ(headings.fitted(), 1);
  const Pose2 after = *correction * scans.back().odometry;
  EXPECT_NEAR(wrapAngle(after.theta - kLast.theta), 0.015, 0.002) << "half of the turn";
}

TEST(WallHeadingTrackerTest, WallsOffTheAxesOrOffChangeNothing) {
  WallHeadingConfig c;
  c.gain = 1.0;
  c.period = 1;
  WallHeadingTracker headings(c);
  // The same room turned by 20 degrees about its middle: no wall runs along the axes.
  const Pose2 turn = Pose2(3.0, 2.5, 20.0 * M_PI / 180.0) * Pose2(-3.0, -2.5, 0.0);
  std::vector<Segment> turned;
  for (const Segment& s : room()) turned.push_back({turn * s.a, turn * s.b});
  EXPECT_FALSE(headings.update(drifted(Pose2(), turned)).has_value());
  EXPECT_EQ(headings.fitted(), 1);
  EXPECT_EQ(headings.turned(), 0);
  WallHeadingTracker off;  // gain 0: off
  EXPECT_FALSE(off.enabled());
  EXPECT_FALSE(off.update(drifted(Pose2(0.0, 0.0, 0.03), room())).has_value());
  EXPECT_EQ(off.fitted(), 0);
}

TEST(WallHeadingTrackerTest, BadConfigurationNamesTheField) {
  auto refusal = [](const WallHeadingConfig& c) {
    try {
      WallHeadingTracker t(c);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  WallHeadingConfig c;
  c.gain = 1.5;
  EXPECT_NE(refusal(c).find("'gain'"), std::string::npos) << refusal(c);
  c = {};
  c.period = 0;
  EXPECT_NE(refusal(c).find("'period'"), std::string::npos) << refusal(c);
  c = {};
  c.manhattan.bin_m = 0.0;
  EXPECT_NE(refusal(c).find("bin_m"), std::string::npos) << refusal(c);
}

}  // namespace
}  // namespace coopmap
