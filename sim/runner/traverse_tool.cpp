#include "sim/runner/traverse_tool.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/correction/home_return.h"
#include "core/correction/traverse_log.h"
#include "core/io/atomic_file.h"
#include "core/io/yaml_reader.h"
#include "core/localization/scan_alignment.h"
#include "core/mapping/map_io.h"

namespace coopmap {

namespace {

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

// Aligns each stretch of `stretch` used entries to `grid`; one CSV row per stretch.
StretchAlignmentStats alignStretches(const TraverseLog& log, const std::vector<size_t>& used,
                                     const OccupancyGrid& grid, size_t stretch, std::string* csv) {
  StretchAlignmentStats st;
  *csv =
      "first_entry,x,y,theta_deg,turned_in_stretch_deg,points,inliers,aligned,moved_m,"
      "turned_deg\n";
  const ScanAligner aligner(grid);
  std::vector<double> moved_m, turned_deg;
  double sum_m2 = 0.0, sum_deg2 = 0.0, sum_deg = 0.0;
  for (size_t b = 0; b + stretch <= used.size(); b += stretch) {
    std::vector<const RadialMap*> scans;
    for (size_t k = b; k < b + stretch; ++k) scans.push_back(&log.entries[used[k]].scan);
    ++st.stretches;
    const AlignmentResult a = aligner.align(scans, Pose2());
    const Pose2& middle = log.entries[used[b + stretch / 2]].scan.odometry;
    const Pose2 moved = a.correction * middle;
    const double m = (moved.translation() - middle.translation()).norm();
    const double deg = wrapAngle(moved.theta - middle.theta) * 180.0 / M_PI;
    char row[256];
    std::snprintf(
        row, sizeof row, "%zu,%.4f,%.4f,%.3f,%.3f,%d,%d,%d,%.4f,%.4f\n", used[b], middle.x,
        middle.y, middle.theta * 180.0 / M_PI,
        wrapAngle(scans.back()->odometry.theta - scans.front()->odometry.theta) * 180.0 / M_PI,
        a.points, a.inliers, a.ok ? 1 : 0, a.ok ? m : 0.0, a.ok ? deg : 0.0);
    *csv += row;
    if (!a.ok) continue;
    ++st.aligned;
    moved_m.push_back(m);
    turned_deg.push_back(std::abs(deg));
    sum_m2 += m * m;
    sum_deg2 += deg * deg;
    sum_deg += deg;
  }
  if (st.aligned > 0) {
    st.rms_m = std::sqrt(sum_m2 / st.aligned);
    st.rms_deg = std::sqrt(sum_deg2 / st.aligned);
    st.mean_deg = sum_deg / st.aligned;
    st.median_m = quantile(moved_m, 0.5);
    st.median_deg = quantile(turned_deg, 0.5);
    st.p90_m = quantile(moved_m, 0.9);
    st.p90_deg = quantile(turned_deg, 0.9);
  }
  return st;
}

}  // namespace

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
  if (o.align_stretch < 0)
    throw std::invalid_argument("--align-stretch: expected 0 or more entries, got " +
                                std::to_string(o.align_stretch));
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
  const Eigen::Vector2d cells = (hi - lo + 2.0 * margin) / o.resolution;
  if (const std::string problem = mapSizeProblem(std::ceil(cells.x()), std::ceil(cells.y()));
      !problem.empty()) {
    char resolution[32];
    std::snprintf(resolution, sizeof resolution, "%g", o.resolution);
    throw ConfigError("--resolution: the map of " + o.log_file + " at " + resolution +
                      " m per cell would be larger than " +
                      problem.substr(0, problem.find(", got")) + " (" +
                      problem.substr(problem.find("got ") + 4) + "): use a coarser --resolution");
  }
  const OccupancyGrid grid =
      localMap(log, used, MapLimits::covering(lo - margin, hi + margin, o.resolution));
  std::filesystem::create_directories(o.out_dir);
  writeRosMap(grid, o.out_dir, "map");
  std::vector<StampedPose2> path;
  for (size_t i : used) path.push_back({log.entries[i].scan.stamp, log.entries[i].scan.odometry});
  writeMapPng(o.out_dir + "/map.png", grid, {{path, 0, 0, 230}});
  if (o.align_stretch > 0) {
    std::string csv;
    s.alignment = alignStretches(log, used, grid, static_cast<size_t>(o.align_stretch), &csv);
    writeFileAtomic(o.out_dir + "/stretches.csv", csv);
  }
  return s;
}

void printTraverseSummary(const TraverseOptions& o, const TraverseSummary& t) {
  std::printf(
      "%s: %zu entries (%zu used: %.1f s, %.1f m by odometry, %zu turning, %zu straight); "
      "%s/map.{pgm,yaml,png} written\n",
      t.robot.c_str(), t.entries, t.used, t.duration_s, t.path_length_m, t.turns, t.straights,
      o.out_dir.c_str());
  if (o.align_stretch > 0) {
    const StretchAlignmentStats& a = t.alignment;
    std::printf(
        "stretches of %d aligned to the map: %d of %d; moved at their middle: RMS %.3f m, "
        "%.2f deg; median %.3f m, %.2f deg; 90th percentile %.3f m, %.2f deg; mean turn "
        "%+.2f deg\n",
        o.align_stretch, a.aligned, a.stretches, a.rms_m, a.rms_deg, a.median_m, a.median_deg,
        a.p90_m, a.p90_deg, a.mean_deg);
  }
}

}  // namespace coopmap
