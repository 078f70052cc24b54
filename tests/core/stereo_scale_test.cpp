// The odometry's distance scale from stereo: radial maps 1-1.5 m apart along a straight
// corridor, aligned, against the odometry's displacement.
#include "core/correction/stereo_scale.h"

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "tests/core/segment_world.h"

namespace coopmap {
namespace {

using test::Segment;

// A 2 m corridor along x with pilasters (0.3 m wide, 0.2 m deep) on alternate sides every
// 1.5 m: their faces across the corridor pin the position along it.
std::vector<Segment> corridorWithPilasters() {
  std::vector<Segment> walls = {{{-3.0, -1.0}, {31.0, -1.0}}, {{-3.0, 1.0}, {31.0, 1.0}}};
  for (int k = 0; k < 22; ++k) {
    const double x = -1.0 + 1.5 * k, side = k % 2 == 0 ? -1.0 : 1.0;
    walls.push_back({{x, side}, {x, 0.8 * side}});
    walls.push_back({{x, 0.8 * side}, {x + 0.3, 0.8 * side}});
    walls.push_back({{x + 0.3, 0.8 * side}, {x + 0.3, side}});
  }
  return walls;
}

// A stereo-like view from `pose`: 160 columns over 90 degrees, hits within 3.5 m, ranges
// with `sigma` of noise.
RadialMap viewOf(const std::vector<Segment>& walls, const Pose2& pose, std::mt19937& rng,
                 double sigma = 0.01) {
  std::normal_distribution<double> noise(0.0, sigma);
  RadialMap scan;
  scan.odometry = pose;
  scan.max_range = 3.5;
  for (int i = 0; i < 160; ++i) {
    RadialReading r;
    r.bearing = M_PI / 4 - i * (M_PI / 2) / 159.0;
    const double a = pose.theta + r.bearing;
    const double t = test::castRay(walls, pose.translation(), {std::cos(a), std::sin(a)}, 3.5);
    r.kind = t < 0.0 ? RadialKind::kBeyond : RadialKind::kHit;
    r.range = t < 0.0 ? 3.5 : t + noise(rng);
    r.sigma = 0.02;
    scan.readings.push_back(r);
  }
  return scan;
}

// A robot driving along the corridor's middle, 0.1 m per radial map with a small weave,
// whose odometry counts `over` too much of every metre.
TraverseLog driveAlong(const std::vector<Segment>& walls, double over, uint32_t seed,
                       double sigma = 0.01) {
  std::mt19937 rng(seed);
  TraverseLog log;
  log.robot = "r";
  for (int i = 0; i <= 240; ++i) {
    const Pose2 truth(0.1 * i, 0.05 * std::sin(0.05 * i), 0.0);
    TraverseEntry e;
    e.segment = MotionSegment::kStraight;
    e.scan = viewOf(walls, truth, rng, sigma);
    e.scan.stamp = i / 3.0;
    e.scan.odometry = Pose2((1.0 + over) * truth.x, truth.y, truth.theta);
    log.entries.push_back(e);
  }
  return log;
}

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
