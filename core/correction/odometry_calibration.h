// Odometry calibrated online from the home-base fixes (beyond the paper, whose robots
// correct each traverse afterwards but drive every sortie on raw odometry). Each corrected
// sortie's fitted systematic errors (heading drift per metre, turn scale; see
// drift_correction.h) are folded into a running estimate, weighted by the distance driven,
// and the raw odometry of later sorties is corrected increment by increment with it. Since a
// sortie runs on odometry calibrated with the estimate so far, what its correction finds is
// the residual, and adds to the estimate.
#pragma once

#include <optional>

#include "core/correction/drift_correction.h"
#include "core/geometry/pose2.h"

namespace coopmap {

class OdometryCalibration {
 public:
  // `distance_scale` false: the distance scale is left uncalibrated (0), whatever the sorties
  // find. A home-base fix does not observe it (an out-and-back path's distance errors
  // cancel); only loop closures do, weakly, and a closure biased along a corridor turns into
  // a scale error every later sortie drives on, larger than the odometry's own
  // (measured: docs/experiments/2026-12-building-settings.md).
  explicit OdometryCalibration(bool distance_scale = true) : distance_scale_(distance_scale) {}
  // What a corrected sortie found (residual errors of the odometry it ran on) over
  // `length_m` driven. Sorties shorter than min_length_m tell too little and are skipped.
  void addSortie(const OdometryBias& residual, double length_m, double min_length_m = 5.0);
  // Sets the distance scale from elsewhere (e.g. stereo, core/correction/stereo_scale.h);
  // later calls of calibrate() use it.
  void setDistanceScale(double scale) { bias_.distance_scale = scale; }
  const OdometryBias& bias() const { return bias_; }
  double weight_m() const { return weight_m_; }

  // The calibrated odometry pose (X_OR) for a raw one: the raw increment since the last call,
  // corrected with the current estimate, added to the calibrated pose. The first call
  // returns the raw pose (both start at the same pose).
  Pose2 calibrate(const Pose2& raw);

 private:
  bool distance_scale_ = true;
  OdometryBias bias_;
  double weight_m_ = 0.0;
  std::optional<Pose2> last_raw_;
  Pose2 calibrated_;
};

}  // namespace coopmap
