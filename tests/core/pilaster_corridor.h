// A straight corridor with pilasters, seen by a stereo-like sensor from a robot driving along
// it on odometry that over-counts distance: synthetic traverse logs for the distance scale
// stereo measures (core/correction/stereo_scale.h).
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/correction/traverse_log.h"
#include "tests/core/segment_world.h"

namespace coopmap::test {

// A 2 m corridor along x with pilasters (0.3 m wide, 0.2 m deep) on alternate sides every
// 1.5 m: their faces across the corridor pin the position along it.
inline std::vector<Segment> corridorWithPilasters() {
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
inline RadialMap viewOf(const std::vector<Segment>& walls, const Pose2& pose, std::mt19937& rng,
                        double sigma = 0.01) {
  std::normal_distribution<double> noise(0.0, sigma);
  RadialMap scan;
  scan.odometry = pose;
  scan.max_range = 3.5;
  for (int i = 0; i < 160; ++i) {
    RadialReading r;
    r.bearing = M_PI / 4 - i * (M_PI / 2) / 159.0;
    const double a = pose.theta + r.bearing;
    const double t = castRay(walls, pose.translation(), {std::cos(a), std::sin(a)}, 3.5);
    r.kind = t < 0.0 ? RadialKind::kBeyond : RadialKind::kHit;
    r.range = t < 0.0 ? 3.5 : t + noise(rng);
    r.sigma = 0.02;
    scan.readings.push_back(r);
  }
  return scan;
}

// Where the robot of driveAlong truly is at its radial map i: along the corridor's middle,
// 0.1 m per radial map with a small weave.
inline Pose2 alongTheMiddle(int i) { return Pose2(0.1 * i, 0.05 * std::sin(0.05 * i), 0.0); }

// A robot driving alongTheMiddle whose odometry counts `over` too much of every metre.
inline TraverseLog driveAlong(const std::vector<Segment>& walls, double over, uint32_t seed,
                              double sigma = 0.01) {
  std::mt19937 rng(seed);
  TraverseLog log;
  log.robot = "r";
  for (int i = 0; i <= 240; ++i) {
    const Pose2 truth = alongTheMiddle(i);
    TraverseEntry e;
    e.segment = MotionSegment::kStraight;
    e.scan = viewOf(walls, truth, rng, sigma);
    e.scan.stamp = i / 3.0;
    e.scan.odometry = Pose2((1.0 + over) * truth.x, truth.y, truth.theta);
    log.entries.push_back(e);
  }
  return log;
}

}  // namespace coopmap::test
