// The odometry's distance scale from stereo: radial maps 1-1.5 m apart along a straight
// corridor, aligned, against the odometry's displacement.
#include "core/correction/stereo_scale.h"

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "tests/core/pilaster_corridor.h"

namespace coopmap {
namespace {

using test::corridorWithPilasters;
using test::driveAlong;
using test::Segment;
using test::viewOf;

TEST(StereoScaleTest, FindsTheDistanceTheOdometryOverCounts) {
  const std::vector<Segment> walls = corridorWithPilasters();
  for (const double over : {0.0, 0.02, -0.01, 0.05}) {
    const StereoScale s = stereoDistanceScale(driveAlong(walls, over, 7));
    EXPECT_GT(s.pairs, 20) << over;
    EXPECT_NEAR(s.scale(), over, 0.002 + 0.05 * std::abs(over)) << over;
  }
}

// Ranges as noisy as the building's stereo at 2-3 m (3 cm): each later point's nearest
// earlier one lies anywhere across the surface's thickness, and one match leans toward the
// displacement it starts from (on the building's logs it found about 70 % of the scale).
// Matching again from the odometry rescaled to the first figure finds all of it.
TEST(StereoScaleTest, RepeatedPassesFindTheScaleNoisySurfacesHoldBack) {
  const std::vector<Segment> walls = corridorWithPilasters();
  StereoScaleConfig one_pass, three_passes;
  three_passes.passes = 3;
  StereoScale single, repeated;
  for (const uint32_t seed : {11u, 12u, 13u}) {
    const TraverseLog log = driveAlong(walls, 0.02, seed, 0.03);
    single.add(stereoDistanceScale(log, one_pass));
    repeated.add(stereoDistanceScale(log, three_passes));
  }
  EXPECT_NEAR(repeated.scale(), 0.02, 0.001);  // one pass: 0.0186
  EXPECT_LT(single.scale(), repeated.scale());
}

// Hits at a floor's end (RadialReading::floor_edge) lie where the floor stops being matched,
// biased farther the farther they are (the building's rendered frames: 2 cm nearer to 11 cm
// farther than the wall): as the robot closes on a surface its floor's end comes toward it
// faster than the robot drives. Only matched surfaces measure the scale.
TEST(StereoScaleTest, FloorEndsDoNotMeasureTheScale) {
  TraverseLog log = driveAlong(corridorWithPilasters(), 0.02, 7);
  int floor_ends = 0;
  for (TraverseEntry& e : log.entries)
    for (RadialReading& r : e.scan.readings)
      if (r.kind == RadialKind::kHit && r.range < 1.5) {
        r.range *= 1.05;  // 5 % farther
        r.floor_edge = true;
        ++floor_ends;
      }
  ASSERT_GT(floor_ends, 2000);
  const StereoScale s = stereoDistanceScale(log);
  EXPECT_GT(s.pairs, 20);
  EXPECT_NEAR(s.scale(), 0.02, 0.003);  // with the floor's ends: 0.0317
}

TEST(StereoScaleTest, PoolsTraversesAndSkipsTurns) {
  const std::vector<Segment> walls = corridorWithPilasters();
  StereoScale pooled;
  pooled.add(stereoDistanceScale(driveAlong(walls, 0.015, 1)));
  pooled.add(stereoDistanceScale(driveAlong(walls, 0.015, 2)));
  EXPECT_NEAR(pooled.scale(), 0.015, 0.002);
  EXPECT_EQ(StereoScale{}.scale(), 0.0);
  // Turning in place: no straight stretch, no pair.
  TraverseLog turning;
  std::mt19937 rng(3);
  for (int i = 0; i < 60; ++i) {
    TraverseEntry e;
    e.scan = viewOf(walls, Pose2(5.0, 0.0, 0.1 * i), rng);
    e.scan.odometry = Pose2(5.0, 0.0, 0.1 * i);
    turning.entries.push_back(e);
  }
  EXPECT_EQ(stereoDistanceScale(turning).pairs, 0);
}

TEST(StereoScaleTest, ABadSettingIsNamed) {
  StereoScaleConfig config;
  config.max_gap_m = 0.5;  // below min_gap_m
  try {
    stereoDistanceScale(TraverseLog{}, config);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("max_gap_m"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace coopmap
