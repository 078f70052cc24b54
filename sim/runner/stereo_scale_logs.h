// `coopmap stereo-scale RUN...`: the odometry's distance scale measured by the cameras
// (core/correction/stereo_scale.h) over whole runs' traverse logs, pooled over runs: a
// calibration for the robot from logs, as a lab measures its robots' odometry once rather
// than on every mission (a mission's own sorties give a figure a run's geometry biases).
#pragma once

#include <string>
#include <vector>

namespace coopmap {

struct StereoScaleOptions {
  std::vector<std::string> run_dirs;  // `coopmap run` output folders
  std::string robot;                  // only this robot's logs ("": every robot's)
};

struct StereoScaleLog {
  std::string run_dir, robot;
  int pairs = 0;
  double scale = 0.0;  // the log's own figure (0 without pairs)
  double truth = 0.0;  // from the ground truth, if the run has it (NaN otherwise)
};

struct StereoScaleSummary {
  std::vector<StereoScaleLog> logs;
  int pairs = 0;
  double pooled = 0.0;          // every pair of every log (StereoScale::scale)
  double mean = 0.0;            // of the logs' figures (those with pairs)
  double standard_error = 0.0;  // of that mean, from the logs' spread (pairs within a
                                // log share its geometry: their formal weights overstate it)
  int logs_with_pairs = 0;
};

// Each log's entries are set to the run's raw odometry (trajectory_<robot>_odometry.tum:
// the logged poses carry the live corrections) before it is measured. Throws
// std::runtime_error naming the folder or file for a run without logs or trajectories.
StereoScaleSummary runStereoScale(const StereoScaleOptions& options);

// Prints a line per log and the pooled figures.
void printStereoScaleSummary(const StereoScaleSummary& summary);

}  // namespace coopmap
