// Scenario: the robot drives squares; its odometry's heading error must grow with the
// distance driven and the angle turned as the B-14's odometry preset says (mean over seeds
// within the preset's random-walk spread), and three laps must drift about three times one.
#include <cmath>

#include <gtest/gtest.h>

#include "robots/robot_model.h"
#include "sim/runner/world_run.h"
#include "tests/support/test_world.h"

namespace coopmap {
namespace {

test_support::TestWorldFile squareWorld(int laps) {
  std::string route;
  for (int i = 0; i < laps; ++i) route += "[2.0, 0.0], [2.0, 2.0], [0.0, 2.0], [0.0, 0.0], ";
  return test_support::writeTestWorld("square_" + std::to_string(laps),
                                      R"(floor: {min: [-2, -2], max: [4, 4], texture: carpet}
walls: []
)",
                                      route);
}

struct Drift {
  double error = 0.0;      // odometry heading - true heading at the end (rad)
  double predicted = 0.0;  // what the preset's systematic parts predict (rad)
  double sigma = 0.0;      // the preset's random walk (rad)
};

Drift drive(int laps, uint64_t seed, const sim::OdometryConfig& preset) {
  RunOptions o;
  const test_support::TestWorldFile world = squareWorld(laps);
  o.world_file = world.path();
  o.seed = seed;
  o.duration = 40.0 * laps;
  o.steer_by_truth = true;
  o.odometry = "drifting";
  const RunResult r = runWorld(o);
  const RobotRunResult& robot = r.robots[0];
  double turned = 0.0, turned_abs = 0.0;
  for (size_t i = 1; i < robot.groundtruth.size(); ++i) {
    const double d =
        wrapAngle(robot.groundtruth[i].pose.theta - robot.groundtruth[i - 1].pose.theta);
    turned += d;
    turned_abs += std::abs(d);
  }
  Drift drift;
  // Unwrapped: odometry turned (1 + e) times as much, plus drift per metre.
  drift.error = wrapAngle(robot.odometry.back().pose.theta - robot.groundtruth.back().pose.theta);
  drift.predicted = preset.turn_scale_error * turned + preset.heading_drift * robot.path_length_m;
  drift.sigma = std::sqrt(preset.angular_noise * preset.angular_noise * turned_abs +
                          preset.heading_noise * preset.heading_noise * robot.path_length_m);
  return drift;
}

TEST(SquareDriveTest, HeadingErrorGrowsAsThePresetSays) {
  const sim::OdometryConfig preset =
      loadRobotModel(std::string(COOPMAP_SOURCE_DIR) + "/robots/b14/b14.yaml").odometry;
  double mean1 = 0.0, mean3 = 0.0;
  const int seeds = 4;
  for (uint64_t seed = 1; seed <= seeds; ++seed) {
    const Drift one = drive(1, seed, preset), three = drive(3, seed, preset);
    mean1 += one.error / seeds;
    mean3 += three.error / seeds;
    // Each run within 3 sigma of the random walk (plus 0.2 deg for the wheels' own slip).
    EXPECT_NEAR(one.error, one.predicted, 3 * one.sigma + 0.0035) << "seed " << seed;
    EXPECT_NEAR(three.error, three.predicted, 3 * three.sigma + 0.0035) << "seed " << seed;
  }
  std::printf("square, mean heading error: 1 lap %.2f deg, 3 laps %.2f deg\n", mean1 * 180 / M_PI,
              mean3 * 180 / M_PI);
  EXPECT_GT(mean1, 0.02);  // the preset drifts left about 2.9 degrees a lap
  EXPECT_NEAR(mean3 / mean1, 3.0, 0.5);
}

}  // namespace
}  // namespace coopmap
