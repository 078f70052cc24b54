// Scenario: a person walks across in front of a robot that stands still. The person must
// show in the robot's radial maps while crossing, and leave no obstacle in the map once
// the cells are seen free again; a person walking into a robot is a counted contact.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "core/correction/home_return.h"
#include "sim/runner/world_run.h"
#include "tests/support/test_world.h"

namespace coopmap {
namespace {

// A wall 3.8 m ahead of the robot; `people` is the world's people list, `more_robots` robots
// besides r (YAML list items), `more` more of the world. Without a home base, the robot maps
// in its own start frame (the world's here).
test_support::TestWorldFile writeWorld(const std::string& people,
                                       const std::string& more_robots = "",
                                       const std::string& more = "",
                                       const std::string& route = "") {
  return test_support::writeTestWorld("crossing",
                                      R"(floor: {min: [-1, -4], max: [4, 4], texture: carpet}
walls:
  - {from: [3.8, -4], to: [3.8, 4], thickness: 0.1, height: 2.5, texture: poster}
)" + more + people,
                                      route, more_robots);
}

TEST(PeopleScenarioTest, PersonCrossingShowsThenLeavesNoObstacle) {
  // Walks from y = -3.5 to y = 3.5 along x = 2.5, crossing the view from t = 2 s to ~5 s.
  RunOptions o;
  const test_support::TestWorldFile world = writeWorld(R"(people:
  - {name: ann, radius: 0.25, speed: 1.0, start_time: 0.5, path: [[2.5, -3.5], [2.5, 3.5]]}
)");
  o.world_file = world.path();
  o.robots = 1;
  o.duration = 12.0;
  o.odometry = "perfect";
  const RunResult r = runWorld(o);
  const RobotRunResult& robot = r.robots[0];
  // While crossing, some scan sees the person ~2.25 m ahead (the wall is at ~4.85 m).
  int person_scans = 0;
  for (const TraverseEntry& entry : robot.traverse.entries)
    for (const RadialReading& rd : entry.scan.readings)
      if (rd.kind == RadialKind::kHit && rd.range < 2.8) {
        ++person_scans;
        break;
      }
  EXPECT_GE(person_scans, 3);
  EXPECT_EQ(robot.collisions, 0);
  // After the crossing the map holds the wall but not the person: the cells the person
  // walked through (x 2.25..2.75 in view) are seen and none is occupied.
  EXPECT_GE(robot.map.wall_recall, 0.8);
  const MapLimits lim = MapLimits::covering({-1.5, -4.5}, {4.5, 4.5}, 0.05);
  const OccupancyGrid map = localMap(robot.traverse, lim);
  int seen = 0, occupied = 0;
  for (double y = -1.5; y <= 1.5; y += 0.05)
    for (double x = 2.3; x <= 2.7; x += 0.05) {
      const int ix = lim.cellX(x), iy = lim.cellY(y);
      seen += map.seen(ix, iy);
      occupied += map.state(ix, iy) == CellState::kOccupied;
    }
  EXPECT_GT(seen, 400);
  EXPECT_EQ(occupied, 0);
}

TEST(PeopleScenarioTest, ATeammateIsNotLoggedWhereItReportsItself) {
  // r stands facing a teammate 2 m ahead that stands still too, the wall beyond; both look at
  // the home base beside them first (which places them in its frame), and stay. Unmasked, the
  // teammate is an obstacle in what r logs (and would post); masked where it reports itself
  // (perfect odometry: where it is), it is not, and the wall beside it still is, also in what
  // r logged before the teammate was placed. r's own map, which it drives by, shows the
  // teammate either way.
  const test_support::TestWorldFile world =
      writeWorld("",
                 "  - name: mate\n    model: " + std::string(COOPMAP_SOURCE_DIR) +
                     "/robots/b14/b14.yaml\n    start: {position: [2.0, 0.0], heading_deg: 0}\n"
                     "    route: [[2.0, 0.0]]\n",
                 R"(home_base:
  corners:
    - {position: [1.7, 2.5], heading_deg: -90}
    - {position: [0.3, 2.5], heading_deg: -90}
  texture: poster
)",
                 "[0.0, 0.0]");
  for (const double mask : {0.0, 0.5}) {
    RunOptions o;
    o.world_file = world.path();
    o.robots = 2;
    o.duration = 40.0;
    o.odometry = "perfect";
    o.settings = [mask](AgentSettings& s) { s.teammate_mask_m = mask; };
    const RunResult r = runWorld(o);
    ASSERT_EQ(r.robots.size(), 2u);
    ASSERT_TRUE(r.robots[0].grid.has_value());
    ASSERT_TRUE(r.robots[0].placed && r.robots[1].placed);
    const Pose2 X_WM = r.robots[0].map_in_world;
    auto count = [&X_WM](const OccupancyGrid& map, int& on_mate, int& on_wall) {
      const MapLimits& lim = map.limits();
      on_mate = on_wall = 0;
      for (int iy = 0; iy < lim.height; ++iy)
        for (int ix = 0; ix < lim.width; ++ix) {
          if (map.state(ix, iy) != CellState::kOccupied) continue;
          const Eigen::Vector2d c = X_WM * lim.cellCenter(ix, iy);
          on_mate += (c - Eigen::Vector2d(2.0, 0.0)).norm() < 0.35;
          on_wall += std::abs(c.x() - 3.8) < 0.15 && std::abs(c.y()) > 0.6;
        }
    };
    int on_mate = 0, on_wall = 0, own_mate = 0, own_wall = 0;
    count(localMap(r.robots[0].traverse, r.robots[0].grid->limits()), on_mate, on_wall);
    count(*r.robots[0].grid, own_mate, own_wall);
    EXPECT_GE(own_mate, 5) << "mask " << mask << ": r drives by what it sees";
    if (mask == 0.0) {
      EXPECT_GE(on_mate, 5) << "logged like the world";
    } else {
      EXPECT_EQ(on_mate, 0);
    }
    EXPECT_GE(on_wall, 20) << "mask " << mask;
  }
}

TEST(PeopleScenarioTest, PersonWalkingIntoTheRobotIsAContact) {
  RunOptions o;
  const test_support::TestWorldFile world = writeWorld(R"(people:
  - {name: bob, radius: 0.25, speed: 0.8, yield_distance: 0, path: [[3.0, 0.0], [-0.5, 0.0]]}
)");
  o.world_file = world.path();
  o.robots = 1;
  o.duration = 6.0;
  o.odometry = "perfect";
  const RunResult r = runWorld(o);
  EXPECT_GE(r.robots[0].collisions, 1);
  // The kinematic person pushes the robot back.
  EXPECT_LT(r.robots[0].groundtruth.back().pose.x, -0.05);
}

}  // namespace
}  // namespace coopmap
