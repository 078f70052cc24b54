// The odometry preset fitted to the real UTIAS MRCLAM log (robot 1) reproduces the log's
// error statistics on the simulated robot driven by the log's own commands.
#include <filesystem>

#include <gtest/gtest.h>

#include "sim/runner/odometry_fit.h"

namespace coopmap {
namespace {

const std::string kData = std::string(COOPMAP_SOURCE_DIR) + "/../shared/data/utias_mrclam_dataset7";

TEST(OdometryFitTest, FittedPresetReproducesTheRealLog) {
  if (!std::filesystem::exists(kData + "/Robot1_Odometry.dat"))
    GTEST_SKIP() << "UTIAS log not found at " << kData << " (../shared/data is absent)";
  OdometryFitOptions o;
  o.groundtruth = kData + "/Robot1_Groundtruth.dat";
  o.odometry = kData + "/Robot1_Odometry.dat";
  o.robot_model = std::string(COOPMAP_SOURCE_DIR) + "/robots/b14/b14.yaml";
  o.simulate = true;
  const OdometryFitResult r = runOdometryFit(o);
  EXPECT_EQ(r.real.windows, 90);  // 900 s in 10 s windows
  // Measured: heading bias -0.0726 rad/m real vs -0.0780 simulated; scale 0.0797 vs 0.0823.
  EXPECT_NEAR(r.simulated.heading_bias_per_m, r.real.heading_bias_per_m,
              0.15 * std::abs(r.real.heading_bias_per_m));
  EXPECT_NEAR(r.simulated.scale_bias, r.real.scale_bias, 0.15 * std::abs(r.real.scale_bias));
  EXPECT_NEAR(r.simulated.distance_sigma_per_sqrt_m, r.real.distance_sigma_per_sqrt_m,
              0.3 * r.real.distance_sigma_per_sqrt_m);
}

}  // namespace
}  // namespace coopmap
