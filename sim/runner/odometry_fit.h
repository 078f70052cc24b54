// `coopmap odometry-fit`: odometry error growth of a real log with ground truth (UTIAS
// MRCLAM format), a simulator preset fitted to it, and the same statistics of the simulated
// B-14 driven by the log's own velocity commands with that preset.
#pragma once

#include <string>

#include "core/odometry/drift_stats.h"
#include "sim/sensors/odometry.h"

namespace coopmap {

struct OdometryFitOptions {
  std::string groundtruth, odometry;  // UTIAS files
  std::string robot_model;            // the simulated robot (for --simulate)
  double window_s = 10.0;
  bool simulate = false;
  uint64_t seed = 1;
};

struct OdometryFitResult {
  DriftStats real;
  sim::OdometryConfig preset;  // fitted
  DriftStats simulated;        // the preset on the simulated robot (when simulate)
};

// The preset whose errors have these statistics.
sim::OdometryConfig presetFromStats(const DriftStats& s);

OdometryFitResult runOdometryFit(const OdometryFitOptions& options);

}  // namespace coopmap
