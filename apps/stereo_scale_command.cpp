#include "apps/stereo_scale_command.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "core/correction/stereo_scale.h"
#include "core/correction/traverse_log.h"
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
  StereoScaleConfig config;
  config.passes = o.passes;
  config.validate();
  StereoScaleSummary s;
  StereoScale pooled;
  for (const std::string& dir : o.run_dirs) {
    std::vector<std::filesystem::path> logs;
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
      const std::string name = e.path().filename().string();
      if (name.rfind("traverse_", 0) == 0 && e.path().extension() == ".traverse")
        logs.push_back(e.path());
    }
    std::sort(logs.begin(), logs.end());
    size_t used = 0;
    for (const std::filesystem::path& path : logs) {
      const std::string robot = path.stem().string().substr(std::string("traverse_").size());
      if (!o.robot.empty() && robot != o.robot) continue;
      ++used;
      TraverseLog log = loadTraverseLog(path.string());
      const std::string odometry_file = dir + "/trajectory_" + robot + "_odometry.tum";
      const std::vector<StampedPose2> odometry = readTum(odometry_file);
      std::vector<StampedPose2> truth;
      const std::string truth_file = dir + "/trajectory_" + robot + "_groundtruth.tum";
      if (std::filesystem::exists(truth_file)) truth = readTum(truth_file);
      std::vector<Pose2> raw;
      std::vector<const Pose2*> true_poses;
      for (TraverseEntry& e : log.entries) {
        const Pose2* p = tumPoseAt(odometry, e.scan.stamp);
        if (!p)
          throw std::runtime_error(odometry_file + ": no pose stamped " +
                                   std::to_string(e.scan.stamp) + " s (an entry of " +
                                   path.string() + ")");
        e.scan.odometry = *p;
        raw.push_back(*p);
        true_poses.push_back(truth.empty() ? nullptr : tumPoseAt(truth, e.scan.stamp));
      }
      const StereoScale measured = stereoDistanceScale(log, config);
      pooled.add(measured);
      StereoScaleLog row;
      row.run_dir = dir;
      row.robot = robot;
      row.pairs = measured.pairs;
      row.scale = measured.scale();
      row.truth =
          truth.empty() ? std::numeric_limits<double>::quiet_NaN() : trueScale(raw, true_poses);
      s.logs.push_back(row);
    }
    if (used == 0)
      throw std::runtime_error(dir + ": no traverse_" + (o.robot.empty() ? "<robot>" : o.robot) +
                               ".traverse log in the folder");
  }
  s.pairs = pooled.pairs;
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

}  // namespace coopmap
