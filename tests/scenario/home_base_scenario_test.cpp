// Scenario: the paper's home-base protocol in the lab. The robot maps the home base while
// turning in place at the start, tours the lab on drifting odometry, turns in place at home
// again, finds the two corners in that local map, and corrects its pose. The corrected
// pose is compared with the simulator's true pose.
//
// Measured with noise-free cameras (seeds 1-3): 0.33 m / 6.9 deg of drift corrected to
// 2.7 cm / 0.77 deg, 0.43 m / 8.0 deg to 3.3 cm / 0.40 deg; seed 3 finds no first corner at
// return. With the B-14's default camera noise the corner search fails on 2 of 3 seeds.
// The goal of issue 5 is 2 cm / 0.5 deg on every seed, with noise: these bounds guard what
// works now, not that goal.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "apps/run_world.h"
#include "core/localization/home_base.h"
#include "sim/world/world.h"

namespace coopmap {
namespace {

const std::string kLab = std::string(COOPMAP_SOURCE_DIR) + "/worlds/lab.yaml";

// The scans of the robot's turn in place at the start (first) or at the end (last) of the
// run that look at the home base (its midpoint within 40 degrees of the heading): the few
// seconds the robot spends facing it, so odometry drift within the turn hardly matters.
std::vector<RadialMap> homeBaseScans(const std::vector<RadialMap>& all, bool at_end,
                                     const Eigen::Vector2d& home_base) {
  std::vector<RadialMap> turn;
  if (all.empty()) return turn;
  const Pose2 anchor = at_end ? all.back().odometry : all.front().odometry;
  auto near = [&](const RadialMap& r) {
    return std::hypot(r.odometry.x - anchor.x, r.odometry.y - anchor.y) < 0.05;
  };
  if (at_end) {
    for (auto it = all.rbegin(); it != all.rend() && near(*it); ++it)
      turn.insert(turn.begin(), *it);
  } else {
    for (auto it = all.begin(); it != all.end() && near(*it); ++it) turn.push_back(*it);
  }
  std::vector<RadialMap> out;
  for (const RadialMap& r : turn) {
    const Eigen::Vector2d to = home_base - r.odometry.translation();
    if (std::abs(wrapAngle(std::atan2(to.y(), to.x()) - r.odometry.theta)) < 40.0 * M_PI / 180)
      out.push_back(r);
  }
  return out;
}

// The pose of a trajectory at a time (the sample at or just before it).
Pose2 poseAt(const std::vector<StampedPose2>& t, double stamp) {
  Pose2 p = t.front().pose;
  for (const StampedPose2& s : t)
    if (s.stamp <= stamp + 1e-9) p = s.pose;
  return p;
}

TEST(HomeBaseScenarioTest, DriftingTourIsCorrectedAtHome) {
  const sim::World world = sim::loadWorld(kLab);
  const Eigen::Vector2d c1 = world.home_base.corners[0].position;
  const Eigen::Vector2d c2 = world.home_base.corners[1].position;
  const Eigen::Vector2d start = world.robots[0].start.translation();
  MapLimits lim =
      MapLimits::covering(start - Eigen::Vector2d(3, 3), start + Eigen::Vector2d(3, 3), 0.025);
  CornerConfig corners;
  corners.arm_cells = world.home_base.arm_length / lim.resolution;

  int localized = 0;
  for (uint64_t seed : {1, 2, 3}) {
    RunOptions o;
    o.world_file = kLab;
    o.seed = seed;
    o.robots = 1;
    o.odometry = "drifting";
    o.camera_noise = false;  // see above
    const RunResult run = runWorld(o);
    const RobotRunResult& jose = run.robots[0];
    ASSERT_TRUE(jose.route_complete);
    const Eigen::Vector2d mid = 0.5 * (c1 + c2);
    const auto first = homeBaseScans(jose.traverse, false, mid);
    const auto last = homeBaseScans(jose.traverse, true, mid);
    ASSERT_GE(first.size(), 4u);
    ASSERT_GE(last.size(), 4u);

    // At the start odometry is the map frame: register the corners near where they stand.
    const CornerDetector at_start(classifyCells(localMap(first, lim)), corners);
    const HomeBaseRegistration reg = registerHomeBase(at_start, c1, c2, 0.3);
    ASSERT_TRUE(reg.home.has_value()) << "seed " << seed << ": " << toString(reg.status);

    // Back home: the corners where drifted odometry puts them; the fix holds at the time
    // of the last scan of the home base.
    const double t = last.back().stamp;
    const Pose2 odometry = poseAt(jose.odometry, t), truth = poseAt(jose.groundtruth, t);
    const OccupancyGrid end_map = localMap(last, lim);
    const CornerDetector at_end(classifyCells(end_map), corners);
    const HomeBaseFix fix = localizeAtHomeBase(at_end, *reg.home, odometry, 1.0);
    if (fix.status != HomeBaseStatus::kOk) {
      std::printf("seed %llu: home base not found at return (%zu and %zu scans; %s, %s)\n",
                  static_cast<unsigned long long>(seed), first.size(), last.size(),
                  toString(at_end.findNear(reg.home->first.position, 1.0).status),
                  toString(at_end.findNear(reg.home->second.position, 1.0).status));
      continue;
    }
    ++localized;
    const double before_m = std::hypot(odometry.x - truth.x, odometry.y - truth.y);
    const double before_deg = std::abs(wrapAngle(odometry.theta - truth.theta)) * 180 / M_PI;
    const double after_m = std::hypot(fix.pose.x - truth.x, fix.pose.y - truth.y);
    const double after_deg = std::abs(wrapAngle(fix.pose.theta - truth.theta)) * 180 / M_PI;
    std::printf(
        "seed %llu: odometry error %.3f m %.2f deg -> home-base fix %.4f m %.3f deg "
        "(corner RMS %.2f cells)\n",
        static_cast<unsigned long long>(seed), before_m, before_deg, after_m, after_deg, fix.rms);
    EXPECT_GT(before_m, 0.1) << "seed " << seed << ": the tour should have drifted";
    EXPECT_LE(after_m, 0.05) << "seed " << seed;
    EXPECT_LE(after_deg, 1.0) << "seed " << seed;
  }
  EXPECT_GE(localized, 2);
}

}  // namespace
}  // namespace coopmap
