#include "core/mapping/occupancy_grid.h"

#include <vector>

#include <gtest/gtest.h>

#include "tests/support/radial_reading.h"

namespace coopmap {
namespace {

// A 12 x 5 grid of 0.1 m cells with the sensor at the centre of cell (0, 2).
MapLimits smallLimits() {
  MapLimits l;
  l.resolution = 0.1;
  l.origin = {0.0, 0.0};
  l.width = 12;
  l.height = 5;
  return l;
}

RadialMap scan(std::vector<RadialReading> readings) {
  RadialMap m;
  m.sensor_origin = {0.0, 0.0};
  m.max_range = 1.0;
  m.readings = std::move(readings);
  return m;
}

std::vector<int> row(const OccupancyGrid& g, int iy) {
  std::vector<int> v;
  for (int ix = 0; ix < g.limits().width; ++ix) v.push_back(g.logOdds(ix, iy));
  return v;
}

const Pose2 kSensorPose(0.05, 0.25, 0.0);

TEST(OccupancyGridTest, FreesCellsAlongRayAndMarksTheHit) {
  OccupancyGrid g(smallLimits(), OccupancyConfig{});
  g.insert(scan({hit(0.0, 0.69, 0.01)}), kSensorPose);
  // Cells 0..6 are crossed (-40); cell 7 (centre 0.70 m from the sensor) holds the return:
  // 90 * (1 - 0.01 / 0.05) on the triangle of the half-cell-wide uncertainty region.
  EXPECT_EQ(row(g, 2), (std::vector<int>{-40, -40, -40, -40, -40, -40, -40, 72, 0, 0, 0, 0}));
  EXPECT_EQ(row(g, 1), std::vector<int>(12, 0));
  EXPECT_TRUE(g.seen(7, 2));
  EXPECT_FALSE(g.seen(8, 2));
  EXPECT_EQ(g.state(7, 2), CellState::kOccupied);
  EXPECT_EQ(g.state(3, 2), CellState::kUnknown);  // one scan is not yet enough to call it free
  g.insert(scan({hit(0.0, 0.69, 0.01)}), kSensorPose);
  EXPECT_EQ(g.state(3, 2), CellState::kFree);
}

TEST(OccupancyGridTest, UncertainReturnSpreadsWeakerEvidence) {
  OccupancyGrid g(smallLimits(), OccupancyConfig{});
  g.insert(scan({hit(0.0, 0.73, 0.2)}), kSensorPose);  // half-width 0.2 m = 2 cells
  const std::vector<int> r = row(g, 2);
  // Free up to range - 0.2 m; then a triangle peaking at the range, scaled by 0.1 / 0.2
  // (peak 45), with a floor of a quarter of the peak inside the region.
  EXPECT_EQ(r, (std::vector<int>{-40, -40, -40, -40, -40, -40, 16, 38, 29, 11, 0, 0}));
  EXPECT_FALSE(g.seen(8, 2));  // behind the surface: evidence, but not observed
}

TEST(OccupancyGridTest, OneScanUpdatesACellOnceAndOccupiedWins) {
  OccupancyGrid g(smallLimits(), OccupancyConfig{});
  // Two columns along the same bearing: the farther one's ray crosses the nearer hit.
  g.insert(scan({hit(0.0, 0.69, 0.01), hit(0.0, 0.99, 0.01)}), kSensorPose);
  EXPECT_EQ(row(g, 2), (std::vector<int>{-40, -40, -40, -40, -40, -40, -40, 72, -40, -40, 72, 0}));
}

TEST(OccupancyGridTest, BeyondRangeFreesUpToMaxRange) {
  OccupancyGrid g(smallLimits(), OccupancyConfig{});
  RadialReading r;
  r.kind = RadialKind::kBeyond;
  r.range = 0.5;
  g.insert(scan({r}), kSensorPose);
  EXPECT_EQ(row(g, 2), (std::vector<int>{-40, -40, -40, -40, -40, -40, 0, 0, 0, 0, 0, 0}));
}

TEST(OccupancyGridTest, NoReturnChangesNothing) {
  OccupancyGrid g(smallLimits(), OccupancyConfig{});
  g.insert(scan({RadialReading{}}), kSensorPose);
  for (int iy = 0; iy < 5; ++iy) EXPECT_EQ(row(g, iy), std::vector<int>(12, 0));
}

TEST(OccupancyGridTest, LogOddsAreClamped) {
  OccupancyConfig c;
  c.clamp = 200;
  OccupancyGrid g(smallLimits(), c);
  for (int i = 0; i < 10; ++i) g.insert(scan({hit(0.0, 0.69, 0.01)}), kSensorPose);
  EXPECT_EQ(g.logOdds(7, 2), 200);
  EXPECT_EQ(g.logOdds(0, 2), -200);
}

TEST(OccupancyGridTest, RaysFollowTheRobotPose) {
  OccupancyGrid g(smallLimits(), OccupancyConfig{});
  // Robot at (0.55, 0.05) facing +y; the column at bearing 0 looks straight up the grid.
  g.insert(scan({hit(0.0, 0.29, 0.01)}), Pose2(0.55, 0.05, M_PI / 2));
  EXPECT_EQ(g.logOdds(5, 0), -40);
  EXPECT_EQ(g.logOdds(5, 2), -40);
  EXPECT_EQ(g.logOdds(5, 3), 72);
  EXPECT_EQ(g.logOdds(4, 3), 0);
}

TEST(OccupancyGridTest, ConfigValidationNamesTheField) {
  OccupancyConfig c;
  c.free_delta = 5;
  try {
    OccupancyGrid g(smallLimits(), c);
    FAIL() << "expected an exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'free_delta'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace coopmap
