#include "sim/runner/stereo_scale_logs.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "core/correction/stereo_scale.h"
#include "core/correction/traverse_log.h"
#include "core/io/robot_outputs.h"
#include "core/io/tum.h"

namespace coopmap {

namespace {

// The true distance scale of the odometry over the log: driven (odometry) over true path
// length, entry to entry.
double trueScale(const std::vector<Pose2>& odometry, const std::vector<const Pose2*>& truth) {
  double driven = 0.0, travelled = 0.0;
  for (size_t i = 1; i < odometry.size(); ++i) {
    if (!truth[i] || !truth[i - 1]) return std::numeric_limits<double>::quiet_NaN();
    driven += (odometry[i].translation() - odometry[i - 1].translation()).norm();
    travelled += (truth[i]->translation() - truth[i - 1]->translation()).norm();
  }
  return travelled > 0.0 ? driven / travelled - 1.0 : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

StereoScaleSummary runStereoScale(const StereoScaleOptions& o) {
  if (o.run_dirs.empty()) throw std::invalid_argument("stereo-scale: expected run folders");
  const StereoScaleConfig config;
  StereoScaleSummary s;
  StereoScale pooled;
  for (const std::string& dir : o.run_dirs) {
    size_t used = 0;
    for (const RunLog& run_log : runLogsIn(dir)) {
      const std::string& robot = run_log.robot;
      if (!o.robot.empty() && robot != o.robot) continue;
      ++used;
      TraverseLog log = loadTraverseLog(run_log.path);
      const std::string odometry_file = run_log.trajectory("odometry");
      const std::vector<StampedPose2> odometry = readTum(odometry_file);
      std::vector<StampedPose2> truth;
      const std::string truth_file = run_log.trajectory("groundtruth");
      if (std::filesystem::exists(truth_file)) truth = readTum(truth_file);
      std::vector<Pose2> raw;
      std::vector<const Pose2*> true_poses;
      for (TraverseEntry& e : log.entries) {
        const Pose2* p = tumPoseAt(odometry, e.scan.stamp);
        if (!p)
          throw std::runtime_error(odometry_file + ": no pose stamped " +
                                   std::to_string(e.scan.stamp) + " s (an entry of " +
                                   run_log.path + ")");
        e.scan.odometry = *p;
        raw.push_back(*p);
        true_poses.push_back(truth.empty() ? nullptr : tumPoseAt(truth, e.scan.stamp));
      }
      const StereoScale measured = stereoDistanceScale(log, config);
      pooled.add(measured);
      StereoScaleLog row;
      row.run_dir = dir;
      row.robot = robot;
      row.pairs = measured.pairs();
      row.scale = measured.scale();
      row.truth =
          truth.empty() ? std::numeric_limits<double>::quiet_NaN() : trueScale(raw, true_poses);
      s.logs.push_back(row);
    }
    if (used == 0)
      throw std::runtime_error(dir + ": no traverse_" + (o.robot.empty() ? "<robot>" : o.robot) +
                               ".traverse log in the folder");
  }
  s.pairs = pooled.pairs();
  s.pooled = pooled.scale();
  double sum = 0.0, sq = 0.0;
  for (const StereoScaleLog& l : s.logs)
    if (l.pairs > 0) {
      ++s.logs_with_pairs;
      sum += l.scale;
    }
  if (s.logs_with_pairs > 0) s.mean = sum / s.logs_with_pairs;
  for (const StereoScaleLog& l : s.logs)
    if (l.pairs > 0) sq += (l.scale - s.mean) * (l.scale - s.mean);
  if (s.logs_with_pairs > 1)
    s.standard_error = std::sqrt(sq / (s.logs_with_pairs - 1) / s.logs_with_pairs);
  return s;
}

void printStereoScaleSummary(const StereoScaleSummary& r) {
  for (const StereoScaleLog& l : r.logs) {
    std::printf("%s %s: %d pairs, distance scale %+.4f", l.run_dir.c_str(), l.robot.c_str(),
                l.pairs, l.scale);
    if (std::isfinite(l.truth)) std::printf(" (true %+.4f)", l.truth);
    std::printf("\n");
  }
  std::printf(
      "pooled over %d pairs: %+.4f; mean of %d logs: %+.4f, standard error %.4f (from the logs' "
      "spread)\n",
      r.pairs, r.pooled, r.logs_with_pairs, r.mean, r.standard_error);
}

}  // namespace coopmap
