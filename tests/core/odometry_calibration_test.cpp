// Online odometry calibration: with the systematic errors a fix found, the raw odometry of
// a later drive is corrected increment by increment and ends near the truth; sorties' residual
// findings are averaged by distance.
#include <cmath>

#include <gtest/gtest.h>

#include "core/correction/odometry_calibration.h"

namespace coopmap {
namespace {

// Raw odometry of a true increment under systematic errors (the inverse of the correction
// model: distance scaled, heading drifting per metre, turns scaled).
Pose2 rawIncrement(double ds, double dtheta, const OdometryBias& b) {
  const double raw_ds = ds * (1.0 + b.distance_scale);
  const double raw_dtheta = dtheta * (1.0 + b.turn_scale) + b.heading_drift * std::abs(raw_ds);
  const double phi = 0.5 * raw_dtheta;  // the chord of the raw arc
  return Pose2(raw_ds * std::cos(phi), raw_ds * std::sin(phi), raw_dtheta);
}

TEST(OdometryCalibrationTest, CalibratedOdometryEndsNearTheTruth) {
  OdometryBias bias;
  bias.heading_drift = 0.0055;
  bias.turn_scale = 0.01;
  bias.distance_scale = 0.01;
  // A 20 m square-ish drive: straights of 5 m in 5 cm steps, quarter turns in place.
  Pose2 truth, raw;
  OdometryCalibration calibration;
  OdometryCalibration uncalibrated;
  calibration.addSortie(bias, 30.0);
  EXPECT_NEAR(calibration.bias().heading_drift, 0.0055, 1e-12);
  calibration.calibrate(raw);
  uncalibrated.calibrate(raw);
  Pose2 calibrated, plain;
  for (int side = 0; side < 4; ++side) {
    for (int i = 0; i < 100; ++i) {
      truth = truth * Pose2(0.05, 0.0, 0.0);
      raw = raw * rawIncrement(0.05, 0.0, bias);
      calibrated = calibration.calibrate(raw);
      plain = uncalibrated.calibrate(raw);
    }
    for (int i = 0; i < 18; ++i) {
      truth = truth * Pose2(0.0, 0.0, M_PI / 36.0);
      raw = raw * rawIncrement(0.0, M_PI / 36.0, bias);
      calibrated = calibration.calibrate(raw);
      plain = uncalibrated.calibrate(raw);
    }
  }
  const double raw_error = std::hypot(plain.x - truth.x, plain.y - truth.y);
  const double error = std::hypot(calibrated.x - truth.x, calibrated.y - truth.y);
  EXPECT_GT(raw_error, 0.2);
  EXPECT_LT(error, 0.01);
  EXPECT_LT(std::abs(wrapAngle(calibrated.theta - truth.theta)), 1e-3);
  EXPECT_GT(std::abs(wrapAngle(plain.theta - truth.theta)), 0.1);
}

TEST(OdometryCalibrationTest, ResidualsAreAveragedByDistance) {
  OdometryCalibration c;
  OdometryBias first;
  first.heading_drift = 0.004;
  c.addSortie(first, 10.0);
  OdometryBias residual;  // the next sortie, on odometry calibrated with 0.004, finds 0.002 more
  residual.heading_drift = 0.002;
  c.addSortie(residual, 30.0);
  EXPECT_NEAR(c.bias().heading_drift, 0.004 + 0.75 * 0.002, 1e-12);
  EXPECT_DOUBLE_EQ(c.weight_m(), 40.0);
  OdometryBias noise;
  noise.heading_drift = 0.05;
  c.addSortie(noise, 2.0);  // too short to tell: skipped
  EXPECT_NEAR(c.bias().heading_drift, 0.0055, 1e-12);
}

TEST(OdometryCalibrationTest, TheDistanceScaleIsLeftAloneWhenAskedTo) {
  OdometryBias found;
  found.heading_drift = 0.005;
  found.distance_scale = 0.04;
  OdometryCalibration with, without(false);
  with.addSortie(found, 10.0);
  without.addSortie(found, 10.0);
  EXPECT_DOUBLE_EQ(with.bias().distance_scale, 0.04);
  EXPECT_DOUBLE_EQ(without.bias().distance_scale, 0.0);
  EXPECT_DOUBLE_EQ(without.bias().heading_drift, 0.005);
  // 10 m straight on raw odometry: without the scale the calibrated pose is 10 m from the
  // start (bent a little by the heading drift), with it 4 % less.
  with.calibrate(Pose2());
  without.calibrate(Pose2());
  EXPECT_NEAR(without.calibrate(Pose2(10.0, 0.0, 0.0)).translation().norm(), 10.0, 0.01);
  EXPECT_NEAR(with.calibrate(Pose2(10.0, 0.0, 0.0)).translation().norm(), 10.0 / 1.04, 0.05);
}

}  // namespace
}  // namespace coopmap
