#include "sim/world/ground_truth.h"

#include <gtest/gtest.h>

namespace coopmap::sim {
namespace {

World boxWorld(double yaw) {
  World w;
  w.floor_min = {0, 0};
  w.floor_max = {4, 4};
  w.map_resolution = 0.1;
  SolidBox b;
  b.center = {2.0, 2.0};
  b.size = {1.0, 0.4, 0.5};
  b.yaw = yaw;
  w.boxes.push_back(b);
  SolidBox high = b;  // a shelf above the robot
  high.center = {1.0, 1.0};
  high.z0 = 1.5;
  w.boxes.push_back(high);
  return w;
}

int count(const GridU8& g) {
  int n = 0;
  for (uint8_t c : g.cells) n += c;
  return n;
}

TEST(GroundTruthTest, AxisAlignedBoxRasterisesToItsCells) {
  const World w = boxWorld(0.0);
  const MapLimits lim = worldMapLimits(w, 0.0);
  ASSERT_EQ(lim.width, 40);
  const GridU8 g = trueOccupancy(w, lim, 1.0);
  // x in [1.5, 2.5] and y in [1.8, 2.2]: 10 x 4 cells. Samples sit at sub-cell centres,
  // so the cells just beyond the edges do not count.
  EXPECT_EQ(count(g), 10 * 4);
  EXPECT_EQ(g.at(15, 18), 1);
  EXPECT_EQ(g.at(24, 21), 1);
  EXPECT_EQ(g.at(25, 21), 0);
  EXPECT_EQ(g.at(10, 10), 0);  // the shelf is above the robot's height
}

TEST(GroundTruthTest, RotatedBoxKeepsItsArea) {
  const GridU8 g = trueOccupancy(boxWorld(M_PI / 4), worldMapLimits(boxWorld(0), 0.0), 1.0);
  // Area 0.4 m^2 = 40 cells; a rotated outline adds partly covered cells along the edges.
  EXPECT_GT(count(g), 40);
  EXPECT_LT(count(g), 75);
  EXPECT_EQ(g.at(20, 20), 1);
}

TEST(GroundTruthTest, FloorMaskCoversTheFloorOnly) {
  const World w = boxWorld(0.0);
  const MapLimits lim = worldMapLimits(w, 0.5);
  const GridU8 m = floorMask(w, lim);
  EXPECT_EQ(count(m), 40 * 40);
  EXPECT_EQ(m.at(0, 0), 0);
  EXPECT_EQ(m.at(5, 5), 1);
}

TEST(GroundTruthTest, FloorMaskOfAreasCoversTheirCellsOnly) {
  World w = boxWorld(0.0);
  w.floor_areas = {{{0, 0}, {4, 1}}, {{3, 1}, {4, 4}}};  // an L inside the 4 m square
  const MapLimits lim = worldMapLimits(w, 0.5);
  const GridU8 m = floorMask(w, lim);
  EXPECT_EQ(count(m), 40 * 10 + 10 * 30);
  const auto at = [&](double x, double y) { return m.at(lim.cellX(x), lim.cellY(y)); };
  EXPECT_EQ(at(0.5, 0.5), 1);
  EXPECT_EQ(at(3.5, 3.5), 1);
  EXPECT_EQ(at(1.5, 2.5), 0);  // in the square, not on the floor
}

}  // namespace
}  // namespace coopmap::sim
