#include "apps/remap_command.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "core/correction/traverse_log.h"
#include "core/io/atomic_file.h"
#include "core/io/tum.h"
#include "core/mapping/map_io.h"
#include "core/mapping/occupancy_grid.h"
#include "robots/robot_model.h"
#include "sim/world/ground_truth.h"
#include "sim/world/world.h"

namespace coopmap {

namespace {

// The pose stamped `stamp` (within a millisecond), if the trajectory has one.
const Pose2* poseAt(const std::vector<StampedPose2>& trajectory, double stamp) {
  const auto it = std::lower_bound(trajectory.begin(), trajectory.end(), stamp - 1e-3,
                                   [](const StampedPose2& p, double t) { return p.stamp < t; });
  if (it == trajectory.end() || std::abs(it->stamp - stamp) > 1e-3) return nullptr;
  return &it->pose;
}

const char* const kOracles = "position, heading, along or across";

}  // namespace

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
  if (!(o.max_error_m >= 0.0) || !std::isfinite(o.max_error_m))
    throw std::invalid_argument("--max-error: expected metres >= 0 (0: every radial map)");
  const sim::World world = sim::loadWorld(o.world_file);
  const MapLimits limits = sim::worldMapLimits(world);
  // Scored as `coopmap run` scores the shared map: against the tallest robot's view.
  double swept = 0.0;
  for (const sim::RobotSpec& r : world.robots)
    swept = std::max(swept, loadRobotModel(r.model_file).description.swept_height);
  const GridU8 truth = sim::trueOccupancy(world, limits, swept);
  const GridU8 floor = sim::floorMask(world, limits);

  RemapSummary s;
  std::vector<std::filesystem::path> logs;
  for (const auto& e : std::filesystem::directory_iterator(o.run_dir)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("traverse_", 0) == 0 && e.path().extension() == ".traverse")
      logs.push_back(e.path());
  }
  std::sort(logs.begin(), logs.end());
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
  for (const std::filesystem::path& path : logs) {
    const TraverseLog& log = loaded.emplace_back(loadTraverseLog(path.string()));
    const std::string robot = path.stem().string().substr(std::string("traverse_").size());
    s.robots.push_back(robot);
    auto trajectory = [&](const std::string& kind) {
      return readTum(o.run_dir + "/trajectory_" + robot + "_" + kind + ".tum");
    };
    std::vector<StampedPose2> poses, truth_poses;
    if (o.poses != "logged") poses = trajectory(o.poses);
    if (o.max_error_m > 0.0 || !o.oracle.empty()) truth_poses = trajectory("groundtruth");
    for (const TraverseEntry& e : log.entries) {
      ++s.entries;
      const Pose2* pose = o.poses == "logged" ? &e.scan.odometry : poseAt(poses, e.scan.stamp);
      if (!pose) {
        ++s.without_pose;
        continue;
      }
      const Pose2* truth = truth_poses.empty() ? nullptr : poseAt(truth_poses, e.scan.stamp);
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
  std::stable_sort(placed.begin(), placed.end(),
                   [](const Placed& a, const Placed& b) { return a.stamp < b.stamp; });
  OccupancyGrid grid(limits, OccupancyConfig{});
  for (const Placed& p : placed) grid.insert(*p.scan, p.pose);
  s.used = placed.size();
  const Eigen::Vector2d home = world.robots.empty() ? limits.origin + Eigen::Vector2d(1, 1)
                                                    : world.robots.front().start.translation();
  s.metrics = computeMapMetrics(grid, truth, home, &floor);
  if (!o.out_dir.empty()) {
    std::filesystem::create_directories(o.out_dir);
    writeRosMap(grid, o.out_dir, "map");
    writeMapPng(o.out_dir + "/map.png", grid, {});
    writeFileAtomic(o.out_dir + "/map_evaluation.png", encodeEvaluationPng(grid, truth, 3, &floor));
  }
  return s;
}

}  // namespace coopmap
