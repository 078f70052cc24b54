// What the mission remembers having seen: a hit stops the robot while it is remembered and
// not seen past, in view or not.
#include <cmath>

#include <gtest/gtest.h>

#include "core/agent/mission_config.h"
#include "core/agent/obstacle_memory.h"
#include "core/geometry/pose2.h"
#include "core/perception/radial_map.h"

namespace coopmap {
namespace {

// 41 columns over +-0.5 rad, left to right (a camera's: bearings decreasing) or the other
// way; the middle one (bearing 0) of `kind` at `range`, the others matched nothing.
RadialMap middleColumn(RadialKind kind, double range, bool left_to_right) {
  RadialMap scan;
  for (int c = 0; c < 41; ++c) {
    RadialReading r;
    r.bearing = (left_to_right ? 20 - c : c - 20) * 0.025;
    if (c == 20) {
      r.kind = kind;
      r.range = range;
    }
    scan.readings.push_back(r);
  }
  return scan;
}

TEST(ObstacleMemoryTest, AHitStopsTheRobotUntilACameraSeesPastIt) {
  for (const bool left_to_right : {true, false}) {
    SCOPED_TRACE(left_to_right ? "columns left to right" : "columns right to left");
    MissionConfig c;
    c.recent_hits_s = 4.0;
    ObstacleMemory memory(c);
    const Pose2 at(1.0, 2.0, 0.5);
    const Pose2 turned(1.0, 2.0, 1.5);  // the hit 1 rad to its right: out of view
    memory.rememberHits(0.0, at, middleColumn(RadialKind::kHit, 1.0, left_to_right));
    EXPECT_TRUE(memory.recentHitAhead(at, 1.2, 0.5));
    EXPECT_FALSE(memory.recentHitAhead(at, 0.8, 0.5));      // farther than that
    EXPECT_FALSE(memory.recentHitAhead(turned, 1.2, 0.5));  // not ahead

    // Turned away, then a column that matches nothing where the hit was: not seen past.
    memory.rememberHits(0.3, turned, middleColumn(RadialKind::kBeyond, 4.0, left_to_right));
    memory.rememberHits(0.6, at, middleColumn(RadialKind::kNone, 0.0, left_to_right));
    EXPECT_TRUE(memory.recentHitAhead(at, 1.2, 0.5));
    // A hit just behind it is the same surface; one well beyond it sees past.
    memory.rememberHits(0.9, at, middleColumn(RadialKind::kHit, 1.1, left_to_right));
    EXPECT_TRUE(memory.recentHitAhead(at, 1.2, 0.5));
    memory.rememberHits(1.2, at, middleColumn(RadialKind::kBeyond, 4.0, left_to_right));
    EXPECT_FALSE(memory.recentHitAhead(at, 1.2, 0.5));
  }
}

}  // namespace
}  // namespace coopmap
