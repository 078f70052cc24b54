// Tracking against the shared map: radial maps of a room, placed at a drifted estimate,
// pull the estimate back towards the truth; in a part of the world the map does not know,
// or off by more than a step may be, nothing changes.
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

}  // namespace
}  // namespace coopmap
