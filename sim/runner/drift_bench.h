// The drift-error benchmark (section 4.1 of the paper, then better): a robot drives the
// long loop of worlds/lab_corridor.yaml on drifting odometry, localizes at the home base,
// and every correction model corrects its traverse and rebuilds its map. Per seed and
// model: odometry and corrected errors, trajectory error against ground truth, map quality
// before and after, and the time to correct and rebuild.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/correction/drift_correction.h"

namespace coopmap {

struct DriftBenchOptions {
  std::string world_file = "worlds/lab_corridor.yaml";
  std::string out_dir;  // drift.csv, drift.md, seeds/<seed>/...; empty: none
  int seeds = 20;       // runs, seeds first_seed, first_seed + 1, ...
  uint64_t first_seed = 1;
  std::string odometry = "drifting";  // preset of the robot file (default: its default)
  bool camera_noise = true;
  std::vector<CorrectionModel> models = allCorrectionModels();
  bool progress = false;  // a line per seed on stderr
};

// One seed and model. Rows of model "ground-truth" rebuild the map from the true poses:
// the best any correction can do with these scans.
struct DriftRow {
  uint64_t seed = 0;
  std::string model;
  std::string status = "ok";  // or why the home base gave no fix
  std::string fix_method;     // how the home-base fix was found
  double path_length_m = 0.0;
  double odometry_error_m = 0.0, odometry_error_deg = 0.0;  // at the home-base fix, uncorrected
  double home_error_m = 0.0, home_error_deg = 0.0;          // home-base fix against truth
  double final_error_m = 0.0, final_error_deg = 0.0;        // corrected, at the fix
  double ate_rmse_m = 0.0, ate_max_m = 0.0, heading_rmse_deg = 0.0;
  double ate_scale_aligned_m = 0.0;  // ATE once a uniform distance scale is taken out
  double drift_percent = 0.0, drift_deg_per_m = 0.0;
  double wall_recall = 0.0, false_occupied_rate = 0.0;
  double correct_ms = 0.0, rebuild_ms = 0.0;
  OdometryBias bias;
  int iterations = 0;
};

struct DriftBenchResult {
  std::vector<DriftRow> rows;
  std::string markdown;  // the summary table, the paper's figures beside ours
};

// Runs the benchmark. Throws ConfigError for bad world or robot files, std::invalid_argument
// for bad options, std::runtime_error when outputs cannot be written.
DriftBenchResult runDriftBench(const DriftBenchOptions& options);

// The CSV text of the rows (header first).
std::string formatDriftCsv(const std::vector<DriftRow>& rows);

}  // namespace coopmap
