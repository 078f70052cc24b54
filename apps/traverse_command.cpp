#include "apps/traverse_command.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "core/correction/home_return.h"
#include "core/correction/traverse_log.h"
#include "core/mapping/map_io.h"

namespace coopmap {

TraverseSummary runTraverse(const TraverseOptions& o) {
  const TraverseLog log = loadTraverseLog(o.log_file);
  TraverseSummary s;
  s.robot = log.robot;
  s.entries = log.entries.size();
  if (log.entries.empty()) throw std::invalid_argument(o.log_file + ": the log has no entries");
  const long n = static_cast<long>(log.entries.size());
  const long last = o.last < 0 ? n - 1 : o.last;
  if (o.first < 0 || o.first > last || last >= n)
    throw std::invalid_argument("--first/--last: expected 0 <= first <= last < " +
                                std::to_string(n) + ", got " + std::to_string(o.first) + ", " +
                                std::to_string(last));
  if (!(o.resolution > 0.0))
    throw std::invalid_argument("--resolution: expected a positive number");
  std::vector<size_t> used;
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  double range = 0.0;
  for (long i = o.first; i <= last; ++i) {
    const TraverseEntry& e = log.entries[i];
    used.push_back(static_cast<size_t>(i));
    lo = lo.cwiseMin(e.scan.odometry.translation());
    hi = hi.cwiseMax(e.scan.odometry.translation());
    range = std::max(range, e.scan.max_range);
    if (i > o.first) {
      const Pose2& a = log.entries[i - 1].scan.odometry;
      s.path_length_m += std::hypot(e.scan.odometry.x - a.x, e.scan.odometry.y - a.y);
    }
    s.turns += e.segment == MotionSegment::kTurn;
    s.straights += e.segment == MotionSegment::kStraight;
  }
  s.used = used.size();
  s.duration_s = log.entries[last].scan.stamp - log.entries[o.first].scan.stamp;
  const Eigen::Vector2d margin(range + 0.5, range + 0.5);
  const OccupancyGrid grid =
      localMap(log, used, MapLimits::covering(lo - margin, hi + margin, o.resolution));
  std::filesystem::create_directories(o.out_dir);
  writeRosMap(grid, o.out_dir, "map");
  std::vector<StampedPose2> path;
  for (size_t i : used) path.push_back({log.entries[i].scan.stamp, log.entries[i].scan.odometry});
  writeMapPng(o.out_dir + "/map.png", grid, {{path, 0, 0, 230}});
  return s;
}

}  // namespace coopmap
