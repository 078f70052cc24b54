// The odometry's distance scale from stereo: radial maps 1-1.5 m apart along a straight
// corridor, aligned, against the odometry's displacement.
#include "core/correction/stereo_scale.h"

#include <cmath>
#include <cstdio>
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
    EXPECT_GT(s.pairs(), 20) << over;
    EXPECT_NEAR(s.scale(), over, 0.002 + 0.05 * std::abs(over)) << over;
  }
}

// The pairs of rendered stereo scatter about ten times as much as their matches claim, and
// some matched the wrong face with all the confidence of a good match: each pair is weighed
// by its claim plus the spread the pairs show, with Huber's weights against the wrong ones.
// Weights from the claims alone (the earlier estimate) give -0.055 here.
TEST(StereoScaleTest, PairsWeighByTheSpreadTheyShowNotOnlyTheirMatchesClaims) {
  std::mt19937 rng(5);
  std::normal_distribution<double> scatter(0.0, 0.03);
  std::uniform_real_distribution<double> claim(0.0005, 0.005);
  StereoScale s;
  for (int i = 0; i < 200; ++i) s.pairs_measured.push_back({0.01 + scatter(rng), claim(rng)});
  for (int i = 0; i < 10; ++i) s.pairs_measured.push_back({-0.08, 0.0002});  // the wrong face
  double claims_only = 0.0, weights = 0.0;
  for (const StereoScale::Pair& p : s.pairs_measured) {
    claims_only += p.over_count / (p.sigma * p.sigma);
    weights += 1.0 / (p.sigma * p.sigma);
  }
  std::printf("from the claims alone %+.4f, with the pairs' spread %+.4f\n", claims_only / weights,
              s.scale());
  EXPECT_NEAR(s.scale(), 0.01, 0.006);  // 3 standard errors of 200 pairs scattered by 3 %
  EXPECT_LT(claims_only / weights, 0.0);
}

// Where the pairs scatter only as their matches claim, the claims weigh them: the precise
// pairs decide (a plain mean of all has a standard error of 0.001 here).
TEST(StereoScaleTest, PairsScatteredAsTheyClaimWeighByTheirClaims) {
  std::mt19937 rng(6);
  StereoScale s;
  double mean = 0.0;
  for (int i = 0; i < 200; ++i) {
    const double sigma = i % 2 == 0 ? 0.001 : 0.02;
    s.pairs_measured.push_back({0.02 + std::normal_distribution<double>(0.0, sigma)(rng), sigma});
    mean += s.pairs_measured.back().over_count / 200.0;
  }
  std::printf("plain mean %+.5f, weighted %+.5f\n", mean, s.scale());
  EXPECT_NEAR(s.scale(), 0.02, 0.0004);  // 4 standard errors of the 100 precise pairs
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
  EXPECT_GT(s.pairs(), 20);
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
  EXPECT_EQ(stereoDistanceScale(turning).pairs(), 0);
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
