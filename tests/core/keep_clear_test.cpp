// Paths that keep clear of walls where the map leaves room (keepClear, and the planner's
// preferred margin): away from a corridor's wall, through a door's middle, and never a
// segment through a cell the robot may not enter, checked on random maps by the planning
// tests' brute-force inflation.
#include "core/planning/keep_clear.h"

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/planning/path_planner.h"
#include "core/planning/planning_map.h"
#include "tests/core/planning_test_maps.h"

namespace coopmap {
namespace {

using planning_test::bfsReachable;
using planning_test::bruteFree;
using planning_test::denseCheck;
using planning_test::randomFreePoint;
using planning_test::randomMap;

// The B-14's body and the default margin.
PlanningMapConfig b14() {
  PlanningMapConfig c;
  c.robot_radius = 0.178;
  c.margin = 0.05;
  return c;
}

// Cells at 5 cm over [0, w] x [0, h] m, occupied where `wall` says.
template <typename Wall>
Grid<CellState> mapOf(double w, double h, Wall wall) {
  MapLimits l;
  l.resolution = 0.05;
  l.width = static_cast<int>(w / l.resolution + 0.5);
  l.height = static_cast<int>(h / l.resolution + 0.5);
  Grid<CellState> g(l, CellState::kFree);
  for (int iy = 0; iy < l.height; ++iy)
    for (int ix = 0; ix < l.width; ++ix)
      if (wall(l.cellCenter(ix, iy))) g.at(ix, iy) = CellState::kOccupied;
  return g;
}

// The least clearance along the path between x0 and x1 (m), sampled every centimetre.
double leastClearance(const std::vector<Eigen::Vector2d>& w, const PlanningMap& m, double x0,
                      double x1) {
  double least = 1e9;
  for (size_t i = 0; i + 1 < w.size(); ++i) {
    const int n = std::max(1, static_cast<int>((w[i + 1] - w[i]).norm() / 0.01));
    for (int k = 0; k <= n; ++k) {
      const Eigen::Vector2d p = w[i] + (w[i + 1] - w[i]) * (static_cast<double>(k) / n);
      if (p.x() >= x0 && p.x() <= x1) least = std::min(least, clearanceAt(m, p));
    }
  }
  return least;
}

// A corridor 2 m wide (walls below y = 0.2 m and from y = 2.2 m), 12 m long.
Grid<CellState> corridor() {
  return mapOf(12.0, 2.4, [](const Eigen::Vector2d& p) { return p.y() < 0.2 || p.y() > 2.2; });
}

TEST(KeepClearTest, ClearanceIsInterpolatedBetweenCellCentres) {
  const PlanningMap m(corridor(), b14());
  // Cell centres at y = 0.175 (wall) and 0.225, 0.275, ...: halfway between two centres the
  // clearance is halfway between theirs.
  EXPECT_NEAR(clearanceAt(m, {5.0, 0.525}), 0.35, 1e-6);
  EXPECT_NEAR(clearanceAt(m, {5.0, 0.55}), 0.375, 1e-6);
  EXPECT_NEAR(clearanceAt(m, {5.0, 1.2}), 1.0, 0.03);  // the middle
}

TEST(KeepClearTest, AWayAlongACorridorsWallMovesToItsMiddle) {
  const Grid<CellState> g = corridor();
  const PlanningMap m(g, b14());
  const Eigen::Vector2d a(1.0, 0.5), b(11.0, 0.5);  // both 0.33 m from the wall
  ASSERT_TRUE(m.segmentFree(a, b));
  const std::vector<Eigen::Vector2d> straight{a, b};
  EXPECT_LT(leastClearance(straight, m, 3.0, 9.0), 0.35);

  KeepClearConfig c;
  c.clearance = 0.178 + 0.5;
  const std::vector<Eigen::Vector2d> w = keepClear(straight, m, c);
  EXPECT_EQ(w.front(), a);
  EXPECT_EQ(w.back(), b);
  EXPECT_LE(w.size(), 2u + static_cast<size_t>(c.max_added));
  for (size_t i = 0; i + 1 < w.size(); ++i) EXPECT_TRUE(m.segmentFree(w[i], w[i + 1]));
  // Away from its ends, the way keeps (nearly) the clearance asked for.
  EXPECT_GT(leastClearance(w, m, 3.0, 9.0), 0.6);
  EXPECT_LT(shortfallOf(w, m, c).integral, 0.2 * shortfallOf(straight, m, c).integral);
  // And the detour is small: the corridor is long.
  double len = 0.0;
  for (size_t i = 0; i + 1 < w.size(); ++i) len += (w[i + 1] - w[i]).norm();
  EXPECT_LT(len, 10.0 * 1.03);
}

TEST(KeepClearTest, ThroughADoorNarrowerThanThePreferenceByItsMiddle) {
  // Two rooms, 3 m each, a 0.1 m wall at x = 3 m with a 0.8 m door at y in [1.6, 2.4] m.
  const Grid<CellState> g = mapOf(6.0, 4.0, [](const Eigen::Vector2d& p) {
    return std::abs(p.x() - 3.0) < 0.05 && (p.y() < 1.6 || p.y() > 2.4);
  });
  const PlanningMap m(g, b14());
  const Pose2 start(1.0, 0.6, 0.0);
  const Eigen::Vector2d goal(5.0, 0.6);
  PlannerConfig plain;
  PlannerConfig clear = plain;
  clear.preferred_margin = 0.5;  // wants 0.68 m: more than the door's half-width
  const PlanResult r0 = PathPlanner(plain).plan(m, start, goal);
  const PlanResult r1 = PathPlanner(clear).plan(m, start, goal);
  ASSERT_TRUE(r0.solved()) << r0.reason;
  ASSERT_TRUE(r1.solved()) << r1.reason;
  const std::vector<uint8_t> free = bruteFree(g, b14());
  EXPECT_EQ(denseCheck(r1.path.waypoints, g.limits, free), "");
  // The string-pulled path shaves a jamb; the clear one passes the door near its middle
  // (0.4 m from both jambs' cell centres).
  EXPECT_LT(leastClearance(r0.path.waypoints, m, 2.8, 3.2), 0.3);
  EXPECT_GT(leastClearance(r1.path.waypoints, m, 2.8, 3.2), 0.34);
  KeepClearConfig want;
  want.clearance = 0.678;
  EXPECT_LT(shortfallOf(r1.path.waypoints, m, want).integral,
            shortfallOf(r0.path.waypoints, m, want).integral);
}

TEST(KeepClearTest, NeverThroughABlockedCellAndNeverLessClear) {
  const PlanningMapConfig c;
  int compared = 0;
  for (uint32_t seed = 1; seed <= 40; ++seed) {
    const Grid<CellState> g = randomMap(seed);
    const std::vector<uint8_t> free = bruteFree(g, c);
    if (std::count(free.begin(), free.end(), 1) < 50) continue;
    const PlanningMap m(g, c);
    std::mt19937 rng(500 + seed);
    const Eigen::Vector2d a = randomFreePoint(rng, g.limits, free);
    const Eigen::Vector2d b = randomFreePoint(rng, g.limits, free);
    if (!bfsReachable(g.limits, free, a, b)) continue;
    PlannerConfig plain;
    plain.seed = seed;
    PlannerConfig clear = plain;
    clear.preferred_margin = 0.3;
    const PlanResult r0 = PathPlanner(plain).plan(m, Pose2(a.x(), a.y(), 0.0), b);
    const PlanResult r1 = PathPlanner(clear).plan(m, Pose2(a.x(), a.y(), 0.0), b);
    SCOPED_TRACE("seed " + std::to_string(seed) + ": " + r1.reason);
    ASSERT_TRUE(r0.solved()) << r0.reason;
    ASSERT_TRUE(r1.solved());
    EXPECT_EQ(denseCheck(r1.path.waypoints, g.limits, free), "");
    EXPECT_EQ(r1.path.waypoints.front(), a);
    EXPECT_EQ(r1.path.waypoints.back(), b);
    KeepClearConfig want;
    want.clearance = c.robot_radius + 0.3;
    EXPECT_LE(shortfallOf(r1.path.waypoints, m, want).integral,
              shortfallOf(r0.path.waypoints, m, want).integral + 1e-9);
    ++compared;
  }
  EXPECT_GE(compared, 20);
}

TEST(KeepClearTest, WithoutAPreferenceThePathIsUnchanged) {
  const PlanningMap m(corridor(), b14());
  const std::vector<Eigen::Vector2d> w{{1.0, 0.5}, {11.0, 0.5}};
  EXPECT_EQ(keepClear(w, m, KeepClearConfig{}), w);
  PlannerConfig bad;
  bad.preferred_margin = -0.1;
  EXPECT_THROW(bad.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace coopmap
