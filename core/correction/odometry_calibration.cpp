#include "core/correction/odometry_calibration.h"

namespace coopmap {

void OdometryCalibration::addSortie(const OdometryBias& residual, double length_m,
                                    double min_length_m) {
  if (!(length_m >= min_length_m)) return;
  // The estimate so far plus this sortie's residual, averaged with the estimate so far by
  // the distance behind each.
  const double w = length_m / (weight_m_ + length_m);
  bias_.heading_drift += w * residual.heading_drift;
  bias_.turn_scale += w * residual.turn_scale;
  if (distance_scale_) bias_.distance_scale += w * residual.distance_scale;
  weight_m_ += length_m;
}

Pose2 OdometryCalibration::calibrate(const Pose2& raw) {
  if (!last_raw_) {
    last_raw_ = raw;
    calibrated_ = raw;
    return calibrated_;
  }
  const Pose2 u = last_raw_->inverse() * raw;
  last_raw_ = raw;
  calibrated_ = calibrated_ * correctedIncrement(u, bias_);
  calibrated_.theta = wrapAngle(calibrated_.theta);
  return calibrated_;
}

}  // namespace coopmap
