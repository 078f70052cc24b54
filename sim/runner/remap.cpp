#include "sim/runner/remap.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "core/correction/traverse_log.h"
#include "core/io/atomic_file.h"
#include "core/io/robot_outputs.h"
#include "core/io/tum.h"
#include "core/mapping/map_io.h"
#include "core/mapping/occupancy_grid.h"
#include "robots/robot_model.h"
#include "sim/world/ground_truth.h"
#include "sim/world/world.h"

namespace coopmap {

namespace {

const char* const kOracles = "position, heading, along or across";

}  // namespace

std::vector<RangeErrorBin> rangeErrors(const std::vector<TrueScan>& scans, const GridU8& truth,
                                       double bin_m, double max_error_m) {
  if (!(bin_m > 0.0) || !(max_error_m > 0.0))
    throw std::invalid_argument("rangeErrors: bin_m and max_error_m must be positive");
  const MapLimits& lim = truth.limits;
  const double step = 0.25 * lim.resolution;
  struct Acc {
    size_t returns = 0, outliers = 0;
    std::vector<double> errors, sigmas;
  };
  std::vector<Acc> acc;
  for (const TrueScan& t : scans) {
    const Eigen::Vector2d origin = t.pose * t.scan->sensor_origin;
    for (const RadialReading& r : t.scan->readings) {
      if (r.kind != RadialKind::kHit) continue;
      const size_t bin = static_cast<size_t>(std::max(0.0, r.range) / bin_m);
      if (bin >= acc.size()) acc.resize(bin + 1);
      Acc& a = acc[bin];
      ++a.returns;
      const double a_ray = t.pose.theta + r.bearing;
      const Eigen::Vector2d d(std::cos(a_ray), std::sin(a_ray));
      // The first occupied cell along the ray, up to max_error_m past the range.
      std::optional<double> surface;
      for (double s = 0.0; s <= r.range + max_error_m; s += step) {
        const Eigen::Vector2d q = origin + s * d;
        const int ix = lim.cellX(q.x()), iy = lim.cellY(q.y());
        if (!lim.contains(ix, iy)) break;
        if (truth.at(ix, iy)) {
          surface = s;
          break;
        }
      }
      if (!surface || std::abs(r.range - *surface) > max_error_m) {
        ++a.outliers;
        continue;
      }
      a.errors.push_back(r.range - *surface);
      a.sigmas.push_back(r.sigma);
    }
  }
  std::vector<RangeErrorBin> out;
  for (size_t b = 0; b < acc.size(); ++b) {
    Acc& a = acc[b];
    if (a.returns == 0) continue;
    RangeErrorBin bin;
    bin.from_m = b * bin_m;
    bin.to_m = (b + 1) * bin_m;
    bin.returns = a.returns;
    bin.outliers = a.outliers;
    const size_t n = a.errors.size();
    if (n > 0) {
      double sum2 = 0.0, sigma = 0.0, within = 0.0;
      for (size_t i = 0; i < n; ++i) {
        sum2 += a.errors[i] * a.errors[i];
        sigma += a.sigmas[i];
        within += std::abs(a.errors[i]) <= a.sigmas[i] ? 1.0 : 0.0;
      }
      bin.rms_m = std::sqrt(sum2 / n);
      bin.mean_sigma_m = sigma / n;
      bin.within_sigma = within / n;
      std::vector<double> e = a.errors;
      std::nth_element(e.begin(), e.begin() + n / 2, e.end());
      bin.median_m = e[n / 2];
      for (double& x : e) x = std::abs(x - bin.median_m);
      std::nth_element(e.begin(), e.begin() + n / 2, e.end());
      bin.robust_sd_m = 1.4826 * e[n / 2];
    }
    out.push_back(bin);
  }
  return out;
}

Pose2 oraclePose(const Pose2& pose, const Pose2& truth, const std::string& oracle) {
  if (oracle.empty()) return pose;
  if (oracle == "position") return Pose2(truth.x, truth.y, pose.theta);
  if (oracle == "heading") return Pose2(pose.x, pose.y, truth.theta);
  if (oracle != "along" && oracle != "across")
    throw std::invalid_argument("--oracle: expected " + std::string(kOracles) + ", got '" + oracle +
                                "'");
  const Eigen::Vector2d u(std::cos(truth.theta), std::sin(truth.theta));
  const Eigen::Vector2d error = pose.translation() - truth.translation();
  const Eigen::Vector2d along = error.dot(u) * u;
  // The part the oracle does not name stays.
  const Eigen::Vector2d kept = oracle == "along" ? error - along : along;
  return Pose2(truth.x + kept.x(), truth.y + kept.y(), pose.theta);
}

RemapSummary runRemap(const RemapOptions& o) {
  const std::vector<std::string> kinds = {"logged", "corrected", "estimate", "odometry",
                                          "groundtruth"};
  if (std::find(kinds.begin(), kinds.end(), o.poses) == kinds.end())
    throw std::invalid_argument(
        "--poses: expected logged, corrected, estimate, odometry or groundtruth, got '" + o.poses +
        "'");
  oraclePose(Pose2(), Pose2(), o.oracle);  // throws for a bad name
  if (o.range_errors && (o.poses != "groundtruth" || !o.oracle.empty()))
    throw std::invalid_argument(
        "--range-errors: expected --poses groundtruth and no --oracle (the errors of the ranges "
        "alone, at the true poses), got --poses " +
        o.poses + (o.oracle.empty() ? "" : " --oracle " + o.oracle));
  if (!(o.max_error_m >= 0.0) || !std::isfinite(o.max_error_m))
    throw std::invalid_argument("--max-error: expected metres >= 0 (0: every radial map)");
  const sim::World world = sim::loadWorld(o.world_file);
  // The run mapped in the home base's frame (coopmap's standard design), or in its first
  // robot's start frame in a world without one.
  const Pose2 X_WM = world.home_base.corners.size() == 2
                         ? sim::mapFrameInWorld(world, HomeBaseDesign{})
                     : world.robots.empty() ? Pose2()
                                            : world.robots.front().start;
  const MapLimits limits = sim::worldMapLimits(world, 0.5, X_WM);
  // Scored as `coopmap run` scores the shared map: against the tallest robot's view.
  double swept = 0.0;
  for (const sim::RobotSpec& r : world.robots)
    swept = std::max(swept, loadRobotModel(r.model_file).description.swept_height);
  const GridU8 truth = sim::trueOccupancy(world, limits, swept, X_WM);
  const GridU8 floor = sim::floorMask(world, limits, X_WM);

  RemapSummary s;
  const std::vector<RunLog> logs = runLogsIn(o.run_dir);
  if (logs.empty())
    throw std::runtime_error(o.run_dir + ": no traverse_<robot>.traverse logs in the folder");
  // Inserted in time order over all robots, as the posts came (with the log-odds clamped,
  // the order matters where cells saturate).
  std::vector<TraverseLog> loaded;
  loaded.reserve(logs.size());  // placed points into them
  struct Placed {
    double stamp;
    const RadialMap* scan;
    Pose2 pose;
  };
  std::vector<Placed> placed;
  for (const RunLog& run_log : logs) {
    const TraverseLog& log = loaded.emplace_back(loadTraverseLog(run_log.path));
    s.robots.push_back(run_log.robot);
    auto trajectory = [&](const std::string& kind) { return readTum(run_log.trajectory(kind)); };
    std::vector<StampedPose2> poses, truth_poses;
    if (o.poses != "logged") poses = trajectory(o.poses);
    if (o.max_error_m > 0.0 || !o.oracle.empty()) truth_poses = trajectory("groundtruth");
    for (const TraverseEntry& e : log.entries) {
      ++s.entries;
      const Pose2* pose = o.poses == "logged" ? &e.scan.odometry : tumPoseAt(poses, e.scan.stamp);
      if (!pose) {
        ++s.without_pose;
        continue;
      }
      const Pose2* truth = truth_poses.empty() ? nullptr : tumPoseAt(truth_poses, e.scan.stamp);
      if (o.max_error_m > 0.0 &&
          (!truth || std::hypot(truth->x - pose->x, truth->y - pose->y) > o.max_error_m)) {
        ++s.too_far;
        continue;
      }
      Pose2 placed_at = *pose;
      if (!o.oracle.empty()) {
        if (!truth) {
          ++s.without_truth;
          continue;
        }
        placed_at = oraclePose(*pose, *truth, o.oracle);
      }
      placed.push_back({e.scan.stamp, &e.scan, placed_at});
    }
  }
  if (placed.empty())
    throw std::runtime_error(o.run_dir + ": none of the " + std::to_string(s.entries) +
                             " radial maps has a " + o.poses + " pose (trajectory_<robot>_" +
                             o.poses + ".tum holds none of their stamps)");
  std::stable_sort(placed.begin(), placed.end(),
                   [](const Placed& a, const Placed& b) { return a.stamp < b.stamp; });
  if (o.range_errors) {
    // The true surfaces on a 1 cm grid: the 5 cm map's cells would add up to 2.5 cm.
    MapLimits fine = limits;
    fine.resolution = 0.01;
    fine.width = static_cast<int>(std::ceil(limits.width * limits.resolution / fine.resolution));
    fine.height = static_cast<int>(std::ceil(limits.height * limits.resolution / fine.resolution));
    std::vector<TrueScan> scans;
    scans.reserve(placed.size());
    for (const Placed& p : placed) scans.push_back({p.scan, p.pose});
    s.range_errors = rangeErrors(scans, sim::trueOccupancy(world, fine, swept, X_WM));
  }
  OccupancyConfig config;
  config.sigma_scale = o.band;
  OccupancyGrid grid(limits, config);
  for (const Placed& p : placed) grid.insert(*p.scan, p.pose);
  s.used = placed.size();
  const Eigen::Vector2d home = world.robots.empty()
                                   ? limits.origin + Eigen::Vector2d(1, 1)
                                   : X_WM.inverse() * world.robots.front().start.translation();
  s.metrics = computeMapMetrics(grid, truth, home, &floor);
  if (!o.out_dir.empty()) {
    std::filesystem::create_directories(o.out_dir);
    writeRosMap(grid, o.out_dir, "map");
    writeMapPng(o.out_dir + "/map.png", grid, {});
    writeFileAtomic(o.out_dir + "/map_evaluation.png", encodeEvaluationPng(grid, truth, 3, &floor));
  }
  return s;
}

void printRemapSummary(const RemapOptions& o, const RemapSummary& r) {
  const MapMetrics& m = r.metrics;
  std::string robots;
  for (const std::string& name : r.robots) robots += (robots.empty() ? "" : ", ") + name;
  const std::string placed =
      o.oracle.empty()         ? o.poses + " poses"
      : o.oracle == "position" ? "true positions with the " + o.poses + " headings"
      : o.oracle == "heading"
          ? o.poses + " positions with the true headings"
          : o.poses + " poses with the position error " +
                (o.oracle == "along" ? "along" : "across") + " the true heading taken out";
  std::printf(
      "%s: %zu radial maps (%s), %zu at their %s, drawn over %.2f of their range sigma (%zu "
      "with no such pose, %zu too far from the truth",
      o.run_dir.c_str(), r.entries, robots.c_str(), r.used, placed.c_str(), o.band, r.without_pose,
      r.too_far);
  if (!o.oracle.empty()) std::printf(", %zu with no true pose", r.without_truth);
  std::printf(
      ")\nwall_recall %.4f false_occupied_rate %.4f coverage %.4f\n"
      "false obstacles by cells to the nearest true one:",
      m.wall_recall, m.false_occupied_rate, m.coverage);
  for (int b = 0; b < MapMetrics::kDistanceBands; ++b)
    std::printf(" %s: %.4f", MapMetrics::kDistanceBandNames[b], m.false_occupied_by_distance[b]);
  std::printf("\n");
  if (!r.range_errors.empty())
    std::printf(
        "range errors (m) by range: returns, outliers (no true surface within 0.5 m), "
        "median, robust sd, RMS, modelled sigma, share within it\n");
  for (const RangeErrorBin& b : r.range_errors)
    std::printf("  %.0f-%.0f m: %zu, %zu, %+.4f, %.4f, %.4f, %.4f, %.3f\n", b.from_m, b.to_m,
                b.returns, b.outliers, b.median_m, b.robust_sd_m, b.rms_m, b.mean_sigma_m,
                b.within_sigma);
}

}  // namespace coopmap
