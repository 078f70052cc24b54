// Scenario: a door that opens on a schedule. Before it opens the robot's stereo sees the
// door and the ground truth holds it; after, both see through to the wall behind; and a
// robot driving at the closed door is stopped by it.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "sim/runner/world_run.h"
#include "sim/world/ground_truth.h"
#include "sim/world/world.h"
#include "tests/support/test_world.h"

namespace coopmap {
namespace {

// A wall with a doorway at x = 2 in front of the robot, a back wall at x = 3.8.
test_support::TestWorldFile writeWorld(const std::string& route) {
  return test_support::writeTestWorld("door",
                                      R"(floor: {min: [-1, -3], max: [4, 3], texture: carpet}
walls:
  - {from: [2, -3], to: [2, -0.6], thickness: 0.1, height: 2.5, texture: poster}
  - {from: [2, 0.6], to: [2, 3], thickness: 0.1, height: 2.5, texture: poster}
  - {from: [3.8, -3], to: [3.8, 3], thickness: 0.1, height: 2.5, texture: poster}
doors:
  - {center: [2, 0], width: 1.2, yaw_deg: 90, open: false, texture: wood,
     schedule: [{at: 6.0, open: true}]}
)",
                                      route);
}

// Median range of the central columns of a radial map (m), or -1 without returns.
double centralRange(const RadialMap& scan) {
  std::vector<double> r;
  const size_t n = scan.readings.size();
  for (size_t i = n / 2 - 5; i < n / 2 + 5; ++i)
    if (scan.readings[i].kind == RadialKind::kHit) r.push_back(scan.readings[i].range);
  if (r.empty()) return -1.0;
  std::sort(r.begin(), r.end());
  return r[r.size() / 2];
}

TEST(DoorScenarioTest, DoorOpensOnScheduleInImagesAndGroundTruth) {
  RunOptions o;
  const test_support::TestWorldFile world_file = writeWorld("");
  o.world_file = world_file.path();
  o.explore = false;  // on the routes: without one, the robot stands and watches the door
  o.duration = 10.0;
  o.odometry = "perfect";
  const RunResult r = runWorld(o);
  const auto& entries = r.robots[0].traverse.entries;
  ASSERT_GT(entries.size(), 20u);
  for (const TraverseEntry& e : entries) {
    const RadialMap& s = e.scan;
    const double range = centralRange(s);
    if (s.stamp < 5.9) {
      EXPECT_NEAR(range, 1.85, 0.15) << "t " << s.stamp;  // the door
    } else if (s.stamp > 6.1) {
      EXPECT_NEAR(range, 3.65, 0.3) << "t " << s.stamp;  // through the doorway
    }
  }
  const sim::World world = sim::loadWorld(o.world_file);
  const MapLimits lim = MapLimits::covering({-1, -3}, {4, 3}, 0.05);
  const int ix = lim.cellX(2.0), iy = lim.cellY(0.0);
  EXPECT_EQ(sim::trueOccupancyAt(world, lim, 1.0, 1.0).at(ix, iy), 1);
  EXPECT_EQ(sim::trueOccupancyAt(world, lim, 1.0, 7.0).at(ix, iy), 0);
}

TEST(DoorScenarioTest, ClosedDoorStopsTheRobot) {
  RunOptions o;
  const test_support::TestWorldFile world_file = writeWorld("[3.0, 0.0]");
  o.world_file = world_file.path();
  o.duration = 5.0;  // the door opens at 6 s
  o.odometry = "perfect";
  const RunResult r = runWorld(o);
  EXPECT_GE(r.robots[0].collisions, 1);
  // Stopped by the door panel (its near face at x = 1.975): the body's front at the door.
  EXPECT_NEAR(r.robots[0].groundtruth.back().pose.x, 1.975 - 0.178, 0.03);
}

}  // namespace
}  // namespace coopmap
