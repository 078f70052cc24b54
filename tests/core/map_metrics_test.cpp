#include "core/mapping/map_metrics.h"

#include <gtest/gtest.h>

namespace coopmap {
namespace {

// Truth: a 12 x 5 grid of 0.1 m cells with a wall filling column 8.
struct Fixture {
  MapLimits lim;
  GridU8 truth;
  Fixture() {
    lim.resolution = 0.1;
    lim.width = 12;
    lim.height = 5;
    truth = GridU8(lim, 0);
    for (int y = 0; y < 5; ++y) truth.at(8, y) = 1;
  }
};

RadialMap oneRay(double range, double sigma = 0.01) {
  RadialMap m;
  RadialReading r;
  r.kind = RadialKind::kHit;
  r.range = range;
  r.sigma = sigma;
  m.readings.push_back(r);
  return m;
}

TEST(MapMetricsTest, CountsWallsFalseObstaclesAndCoverage) {
  Fixture f;
  OccupancyGrid map(f.lim, OccupancyConfig{});
  for (int i = 0; i < 2; ++i) {
    map.insert(oneRay(0.79), Pose2(0.05, 0.25, 0.0));  // sees the wall at cell (8, 2)
    map.insert(oneRay(0.29), Pose2(0.05, 0.05, 0.0));  // a phantom obstacle at cell (3, 0)
  }
  ASSERT_EQ(map.state(8, 2), CellState::kOccupied);
  ASSERT_EQ(map.state(3, 0), CellState::kOccupied);
  const MapMetrics m = computeMapMetrics(map, f.truth, {0.05, 0.25});
  // Wall cells next to seen free space: (8,1), (8,2), (8,3), all within 1 cell of (8,2).
  EXPECT_EQ(m.wall_cells, 3);
  EXPECT_DOUBLE_EQ(m.wall_recall, 1.0);
  // Seen free cells more than one cell from the wall: (0..6, 2) and (0..3, 0); one of
  // them, (3, 0), is marked occupied.
  EXPECT_EQ(m.clear_observed_cells, 11);
  EXPECT_DOUBLE_EQ(m.false_occupied_rate, 1.0 / 11.0);
  // The phantom is 5 cells from the wall.
  for (int b = 0; b < MapMetrics::kDistanceBands; ++b)
    EXPECT_DOUBLE_EQ(m.false_occupied_by_distance[b], b == 2 ? 1.0 / 11.0 : 0.0)
        << MapMetrics::kDistanceBandNames[b];
  // Reachable free space: the 8 x 5 cells left of the wall; seen: (0..7, 2) and (0..3, 0).
  EXPECT_EQ(m.reachable_cells, 40);
  EXPECT_DOUBLE_EQ(m.coverage, 12.0 / 40.0);
}

TEST(MapMetricsTest, FalseObstaclesAreSplitByTheirDistanceToTheTrueOnes) {
  Fixture f;
  OccupancyGrid map(f.lim, OccupancyConfig{});
  for (int i = 0; i < 2; ++i) {
    map.insert(oneRay(0.59), Pose2(0.05, 0.05, 0.0));  // cell (6, 0): 2 cells from the wall
    map.insert(oneRay(0.49), Pose2(0.05, 0.45, 0.0));  // cell (5, 4): 3 cells from it
    map.insert(oneRay(0.09), Pose2(0.05, 0.25, 0.0));  // cell (1, 2): 7 cells from it
  }
  ASSERT_EQ(map.state(6, 0), CellState::kOccupied);
  ASSERT_EQ(map.state(5, 4), CellState::kOccupied);
  ASSERT_EQ(map.state(1, 2), CellState::kOccupied);
  const MapMetrics m = computeMapMetrics(map, f.truth, {0.05, 0.25});
  // Seen, more than a cell from the wall: (0..6, 0), (0..5, 4), (0..1, 2).
  ASSERT_EQ(m.clear_observed_cells, 15);
  const double one = 1.0 / 15.0;
  EXPECT_DOUBLE_EQ(m.false_occupied_by_distance[0], one);
  EXPECT_DOUBLE_EQ(m.false_occupied_by_distance[1], one);
  EXPECT_DOUBLE_EQ(m.false_occupied_by_distance[2], 0.0);
  EXPECT_DOUBLE_EQ(m.false_occupied_by_distance[3], one);
  EXPECT_DOUBLE_EQ(m.false_occupied_by_distance[4], 0.0);
  EXPECT_DOUBLE_EQ(m.false_occupied_rate, 3 * one);
}

TEST(MapMetricsTest, MissedWallLowersRecall) {
  Fixture f;
  OccupancyGrid map(f.lim, OccupancyConfig{});
  // A single uncertain return: cells are seen up to the wall, which is not yet occupied.
  map.insert(oneRay(0.79, 0.18), Pose2(0.05, 0.25, 0.0));
  ASSERT_TRUE(map.seen(7, 2));
  ASSERT_NE(map.state(8, 2), CellState::kOccupied);
  const MapMetrics m = computeMapMetrics(map, f.truth, {0.05, 0.25});
  EXPECT_EQ(m.wall_cells, 3);
  EXPECT_DOUBLE_EQ(m.wall_recall, 0.0);
}

TEST(MapMetricsTest, DrivableMaskLimitsReachableArea) {
  Fixture f;
  OccupancyGrid map(f.lim, OccupancyConfig{});
  GridU8 drivable(f.lim, 1);
  for (int x = 0; x < 12; ++x) drivable.at(x, 4) = 0;  // top row is off the floor
  const GridU8 reach = reachableFree(f.truth, {0.05, 0.25}, &drivable);
  int n = 0;
  for (uint8_t c : reach.cells) n += c;
  EXPECT_EQ(n, 8 * 4);
}

TEST(MapMetricsTest, RejectsMismatchedLimits) {
  Fixture f;
  MapLimits other = f.lim;
  other.width = 11;
  OccupancyGrid map(other, OccupancyConfig{});
  EXPECT_THROW(computeMapMetrics(map, f.truth, {0.05, 0.25}), std::invalid_argument);
}

}  // namespace
}  // namespace coopmap
