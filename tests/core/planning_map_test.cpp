// The planning map: inflation by the robot's radius against a brute-force reference,
// unknown cells, the map's border, exact segment checks through cell corners.
#include "core/planning/planning_map.h"

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/mapping/grid.h"
#include "core/mapping/occupancy_grid.h"
#include "core/robot/robot_interface.h"
#include "tests/core/planning_test_maps.h"

namespace coopmap {
namespace {

using planning_test::bruteFree;
using planning_test::parse;
using planning_test::render;
using planning_test::smallRobot;

TEST(PlanningMapTest, InflatesBlockedCellsAndTheMapBorder) {
  const Grid<CellState> g = parse({".........",  //
                                   ".........",  //
                                   ".........",  //
                                   ".........",  //
                                   "....#....",  //
                                   ".........",  //
                                   ".........",  //
                                   ".........",  //
                                   "........."},
                                  0.1);
  const PlanningMap m(g, smallRobot());
  const std::vector<std::string> expected = {"xxxxxxxxx",  //
                                             "xooooooox",  //
                                             "xooooooox",  //
                                             "xoooxooox",  //
                                             "xooxxxoox",  //
                                             "xoooxooox",  //
                                             "xooooooox",  //
                                             "xooooooox",  //
                                             "xxxxxxxxx"};
  EXPECT_EQ(render(m), expected);
  EXPECT_TRUE(m.blocked(4, 4));
  EXPECT_FALSE(m.blocked(3, 4));
  EXPECT_NEAR(m.clearance(4, 4), 0.0, 1e-9);
  EXPECT_NEAR(m.clearance(2, 4), 0.2, 1e-6);
  EXPECT_NEAR(m.clearance(3, 3), 0.1 * std::sqrt(2.0), 1e-6);
  EXPECT_NEAR(m.clearance(0, 0), 0.1, 1e-6);  // to the ring outside the map
}

TEST(PlanningMapTest, MatchesBruteForceInflationForTheB14) {
  std::mt19937 rng(5);
  MapLimits l;
  l.width = 70;
  l.height = 50;
  Grid<CellState> g(l, CellState::kFree);
  std::uniform_int_distribution<int> cell(0, 69), kind(0, 9);
  for (int k = 0; k < 120; ++k) {
    const int ix = cell(rng), iy = cell(rng) % 50;
    g.at(ix, iy) = kind(rng) < 7 ? CellState::kOccupied : CellState::kUnknown;
  }
  for (bool allow : {false, true}) {
    PlanningMapConfig c;  // B-14: 0.178 m + 0.05 m at 5 cm
    c.allow_unknown = allow;
    const PlanningMap m(g, c);
    const std::vector<uint8_t> expected = bruteFree(g, c);
    int differ = 0, free_cells = 0;
    for (int iy = 0; iy < l.height; ++iy)
      for (int ix = 0; ix < l.width; ++ix) {
        differ += m.free(ix, iy) != (expected[l.index(ix, iy)] != 0);
        free_cells += m.free(ix, iy);
      }
    EXPECT_EQ(differ, 0) << "allow_unknown " << allow;
    EXPECT_GT(free_cells, 100) << "allow_unknown " << allow;  // not trivially all blocked
  }
}

TEST(PlanningMapTest, UnknownCellsBlockUnlessAllowed) {
  const Grid<CellState> g = parse({".......",  //
                                   ".......",  //
                                   ".......",  //
                                   "...?...",  //
                                   ".......",  //
                                   ".......",  //
                                   "......."},
                                  0.1);
  PlanningMapConfig c = smallRobot();
  EXPECT_TRUE(PlanningMap(g, c).blocked(3, 3));
  EXPECT_FALSE(PlanningMap(g, c).free(3, 2));
  c.allow_unknown = true;
  EXPECT_FALSE(PlanningMap(g, c).blocked(3, 3));
  EXPECT_TRUE(PlanningMap(g, c).free(3, 2));
  EXPECT_TRUE(PlanningMap(g, c).free(3, 3));
}

TEST(PlanningMapTest, AnEmptyOccupancyGridIsAllUnknown) {
  MapLimits l;
  l.width = l.height = 20;
  const OccupancyGrid grid(l, OccupancyConfig{});
  PlanningMapConfig c;
  EXPECT_FALSE(PlanningMap(grid, c).free(10, 10));
  c.allow_unknown = true;
  EXPECT_TRUE(PlanningMap(grid, c).free(10, 10));
  EXPECT_FALSE(PlanningMap(grid, c).free(1, 10));  // within the radius of the border
}

TEST(PlanningMapTest, SegmentsCannotSlipBetweenDiagonalNeighbours) {
  // A robot of negligible radius: free cells are exactly the unblocked ones.
  PlanningMapConfig c;
  c.robot_radius = 1e-4;
  c.margin = 0.0;
  const Grid<CellState> g = parse({"......",  //
                                   "......",  //
                                   "..#...",  //
                                   "...#..",  //
                                   "......",  //
                                   "......"},
                                  1.0);
  const PlanningMap m(g, c);
  // Through the corner the two blocked cells share: from the centre of (2, 2) to (3, 3).
  EXPECT_FALSE(m.segmentFree({2.5, 2.5}, {3.5, 3.5}));
  // A hair beside the corner, through the blocked cell (2, 3).
  EXPECT_FALSE(m.segmentFree({2.5, 2.5}, {3.5, 3.5 + 1e-6}));
  // Along free cells only.
  EXPECT_TRUE(m.segmentFree({0.5, 0.5}, {5.5, 0.5}));
  EXPECT_TRUE(m.segmentFree({3.5, 3.5}, {5.5, 5.5}));
  // Where a segment first enters a blocked cell: (0.5, 3.5) -> (5.5, 3.5) enters (2, 3) at x=2.
  const auto t = m.firstBlockedOnSegment({0.5, 3.5}, {5.5, 3.5});
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 1.5 / 5.0, 1e-12);
  EXPECT_EQ(m.firstBlockedOnSegment({2.5, 3.5}, {0.5, 0.5}), 0.0);  // starts blocked
  EXPECT_FALSE(m.segmentFree({0.5, 0.5}, {6.5, 0.5}));              // leaves the map
}

TEST(PlanningMapTest, EveryPartOfAFreeSegmentIsFreeAndBothWaysAgree) {
  // Ends exactly on cell boundaries (a robot's home at (1.3, 2.9) on a 5 cm grid) map to one
  // cell by rounding. The walk once stepped over a boundary met at the very end of a segment:
  // a segment ending on a cell corner next to a blocked cell was blocked while a longer one
  // through the same corner was free, and the planner (whose path simplifier cuts checked
  // segments into parts) returned a path with a blocked segment.
  PlanningMapConfig c;
  c.robot_radius = 1e-4;
  c.margin = 0.0;
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> cell(0, 11);
  std::vector<std::string> rows(12, std::string(12, '.'));
  for (int k = 0; k < 25; ++k) rows[cell(rng)][cell(rng)] = '#';
  const PlanningMap m(parse(rows, 0.05), c);
  std::uniform_int_distribution<int> lattice(0, 24);  // half-cell steps: centres and boundaries
  std::uniform_real_distribution<double> fraction(0.0, 1.0);
  int free_segments = 0;
  for (int k = 0; k < 20000; ++k) {
    const Eigen::Vector2d a(lattice(rng) * 0.025, lattice(rng) * 0.025);
    const Eigen::Vector2d b(lattice(rng) * 0.025, lattice(rng) * 0.025);
    const bool free = m.segmentFree(a, b);
    ASSERT_EQ(free, m.segmentFree(b, a)) << a.transpose() << " -> " << b.transpose();
    if (!free) continue;
    ++free_segments;
    const Eigen::Vector2d s = a + fraction(rng) * (b - a);
    ASSERT_TRUE(m.segmentFree(s, b)) << s.transpose() << " -> " << b.transpose();
    ASSERT_TRUE(m.segmentFree(a, s)) << a.transpose() << " -> " << s.transpose();
  }
  EXPECT_GT(free_segments, 1000);
}

TEST(PlanningMapTest, ValidateNamesTheField) {
  PlanningMapConfig c;
  c.robot_radius = -0.2;
  try {
    c.validate();
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("field 'robot_radius'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("-0.2"), std::string::npos) << e.what();
  }
  c = PlanningMapConfig{};
  c.margin = std::nan("");
  EXPECT_THROW(c.validate(), std::invalid_argument);
  RobotDescription robot;
  robot.body_radius = 0.25;
  EXPECT_EQ(PlanningMapConfig::forRobot(robot).robot_radius, 0.25);
}
}  // namespace
}  // namespace coopmap
