// Scenario: the paper's home-base protocol in the lab. The robot turns in place at the start
// and finds the home base (which places it in the map frame), tours the lab steering by its
// drifting odometry (so it comes back up to half a metre off), turns in place at home again,
// finds the home base in that turn's local map and corrects its pose, all by itself (the
// route is one sortie of the agent); the fix is compared with the true pose.
//
// On the corridor loop, steered by the true pose (the robot back on its start), 20 seeds:
// 18 within 2 cm and 0.5 deg, all within 3.5 cm (`coopmap bench drift`, columns
// home_error_*).
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "sim/runner/world_run.h"

namespace coopmap {
namespace {

const std::string kLab = std::string(COOPMAP_SOURCE_DIR) + "/worlds/lab.yaml";

// The pose of a trajectory at a time (the sample at or just before it).
Pose2 poseAt(const std::vector<StampedPose2>& t, double stamp) {
  Pose2 p = t.front().pose;
  for (const StampedPose2& s : t)
    if (s.stamp <= stamp + 1e-9) p = s.pose;
  return p;
}

TEST(HomeBaseScenarioTest, DriftingTourIsCorrectedAtHome) {
  int localized = 0;
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    RunOptions o;
    o.world_file = kLab;
    o.seed = seed;
    o.robots = 1;
    o.odometry = "drifting";
    const RunResult run = runWorld(o);
    const RobotRunResult& jose = run.robots[0];
    ASSERT_TRUE(jose.route_complete) << "seed " << seed;
    ASSERT_TRUE(jose.placed) << "seed " << seed;
    ASSERT_EQ(jose.sorties, 1) << "seed " << seed << ": the route is one sortie";
    if (jose.fix_errors.empty()) {
      std::printf("seed %llu: no home-base fix (%s)\n", static_cast<unsigned long long>(seed),
                  jose.log.empty() ? "" : jose.log.back().c_str());
      continue;
    }
    ++localized;
    const FixError& fix = jose.fix_errors.front();
    // Before the fix: the robot's estimate as it looked, against the truth.
    const Pose2 before = poseAt(jose.estimate, fix.stamp);
    const Pose2 truth = poseAt(jose.groundtruth, fix.stamp);
    const double before_m = std::hypot(before.x - truth.x, before.y - truth.y);
    const double before_deg = std::abs(wrapAngle(before.theta - truth.theta)) * 180 / M_PI;
    std::printf("seed %llu: estimate off by %.3f m %.2f deg -> home-base fix %.4f m %.3f deg\n",
                static_cast<unsigned long long>(seed), before_m, before_deg, fix.error_m,
                fix.error_deg);
    EXPECT_GT(before_m, 0.1) << "seed " << seed << ": the tour should have drifted";
    EXPECT_LE(fix.error_m, 0.02) << "seed " << seed;
    EXPECT_LE(fix.error_deg, 0.5) << "seed " << seed;
  }
  EXPECT_GE(localized, 8);
}

}  // namespace
}  // namespace coopmap
