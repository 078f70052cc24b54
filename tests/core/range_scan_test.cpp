// Planar range scans as radial maps, and what the occupancy grid makes of them.
#include "core/perception/range_scan.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

#include "core/mapping/occupancy_grid.h"

namespace coopmap {
namespace {

constexpr double kDeg = M_PI / 180.0;

RangeScan fiveBeams() {
  RangeScan s;
  s.stamp = 3.5;
  s.odometry = Pose2(1.0, 2.0, 0.5);
  s.start_angle = -90.0 * kDeg;
  s.angular_resolution = 45.0 * kDeg;
  s.max_range = 8.0;
  s.range_sigma = 0.02;
  s.sensor_origin = Eigen::Vector2d(0.1, 0.0);
  s.ranges = {2.0f, 8.0f, 0.0f, std::numeric_limits<float>::quiet_NaN(), 9.5f};
  return s;
}

TEST(RangeScanTest, BeamsBecomeReadingsInBeamOrder) {
  const RadialMap m = radialMapFromScan(fiveBeams());
  EXPECT_DOUBLE_EQ(m.stamp, 3.5);
  EXPECT_DOUBLE_EQ(m.odometry.theta, 0.5);
  EXPECT_EQ(m.sensor_origin, Eigen::Vector2d(0.1, 0.0));
  EXPECT_DOUBLE_EQ(m.max_range, 8.0);
  ASSERT_EQ(m.readings.size(), 5u);
  for (size_t i = 0; i < 5; ++i)
    EXPECT_NEAR(m.readings[i].bearing, (-90.0 + 45.0 * static_cast<double>(i)) * kDeg, 1e-12);
  // A hit with the scan's sigma.
  EXPECT_EQ(m.readings[0].kind, RadialKind::kHit);
  EXPECT_DOUBLE_EQ(m.readings[0].range, 2.0);
  EXPECT_DOUBLE_EQ(m.readings[0].sigma, 0.02);
  // At the maximum: no return, free up to the maximum.
  EXPECT_EQ(m.readings[1].kind, RadialKind::kBeyond);
  EXPECT_DOUBLE_EQ(m.readings[1].range, 8.0);
  // Zero and NaN: no information.
  EXPECT_EQ(m.readings[2].kind, RadialKind::kNone);
  EXPECT_EQ(m.readings[3].kind, RadialKind::kNone);
  // Beyond the maximum: no return too.
  EXPECT_EQ(m.readings[4].kind, RadialKind::kBeyond);
}

TEST(RangeScanTest, UsableRangeCapsHitsAndFreeSpace) {
  RangeScanConfig c;
  c.max_range = 1.5;
  const RadialMap m = radialMapFromScan(fiveBeams(), c);
  EXPECT_DOUBLE_EQ(m.max_range, 1.5);
  EXPECT_EQ(m.readings[0].kind, RadialKind::kBeyond);  // 2 m hit beyond the usable 1.5 m
  EXPECT_DOUBLE_EQ(m.readings[0].range, 1.5);
  EXPECT_EQ(m.readings[1].kind, RadialKind::kBeyond);
  EXPECT_DOUBLE_EQ(m.readings[1].range, 1.5);

  c.max_range = 0.0;
  c.free_on_no_return = false;
  c.min_sigma = 0.05;
  const RadialMap n = radialMapFromScan(fiveBeams(), c);
  EXPECT_EQ(n.readings[0].kind, RadialKind::kHit);
  EXPECT_DOUBLE_EQ(n.readings[0].sigma, 0.05);
  EXPECT_EQ(n.readings[1].kind, RadialKind::kNone);
  EXPECT_EQ(n.readings[4].kind, RadialKind::kNone);
}

TEST(RangeScanTest, BadScansAndConfigsAreRejectedByName) {
  RangeScan s = fiveBeams();
  s.max_range = 0.0;
  EXPECT_THROW(radialMapFromScan(s), std::invalid_argument);
  RangeScanConfig c;
  c.min_range = -1.0;
  try {
    radialMapFromScan(fiveBeams(), c);
    FAIL() << "negative min_range accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "range scan config: field 'min_range': expected a number >= 0, got -1.000000");
  }
}

// A laser 1 m in front of a wall, through the occupancy grid: the wall's cells become
// occupied, the cells before it free, the cells behind it unknown.
TEST(RangeScanTest, LaserScanMapsAWallSharply) {
  MapLimits lim = MapLimits::covering({-0.5, -1.0}, {2.0, 1.0}, 0.1);
  OccupancyGrid grid(lim, OccupancyConfig{});
  RangeScan s;
  s.max_range = 5.0;
  s.start_angle = -30.0 * kDeg;
  s.angular_resolution = 1.0 * kDeg;
  s.sensor_origin = Eigen::Vector2d(0.2, 0.0);  // the laser 0.2 m ahead of the robot
  for (int i = 0; i <= 60; ++i)
    s.ranges.push_back(static_cast<float>(0.95 / std::cos(s.bearing(static_cast<size_t>(i)))));
  // The wall is at x = 0.2 + 0.95 = 1.15 m, the centre of a column of cells.
  const Pose2 X_WR(0.0, 0.0, 0.0);
  for (int k = 0; k < 3; ++k) grid.insert(radialMapFromScan(s), X_WR);
  const int wall_ix = lim.cellX(1.12);
  for (double y : {-0.3, -0.1, 0.0, 0.1, 0.3}) {
    const int iy = lim.cellY(y);
    EXPECT_EQ(grid.state(wall_ix, iy), CellState::kOccupied) << "y " << y;
    for (double x : {0.3, 0.6, 0.95}) {
      const Eigen::Vector2d c = lim.cellCenter(lim.cellX(x), iy) - s.sensor_origin;
      if (std::abs(c.y()) > std::tan(25.0 * kDeg) * c.x()) continue;  // outside the fan
      EXPECT_EQ(grid.state(lim.cellX(x), iy), CellState::kFree) << x << ", " << y;
    }
    EXPECT_EQ(grid.state(lim.cellX(1.45), iy), CellState::kUnknown) << "behind the wall, y " << y;
  }
  // Nothing is known behind the robot: the laser looks forward.
  EXPECT_EQ(grid.state(lim.cellX(-0.3), lim.cellY(0.0)), CellState::kUnknown);
}

}  // namespace
}  // namespace coopmap
