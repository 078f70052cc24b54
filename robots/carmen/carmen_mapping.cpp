#include "robots/carmen/carmen_mapping.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <utility>

#include "core/io/atomic_file.h"
#include "core/io/carmen_log.h"
#include "core/mapping/map_io.h"
#include "core/perception/range_scan.h"
#include "robots/carmen/carmen_log_robot.h"

namespace coopmap {
void CarmenOptions::validate() const {
  auto bad = [](const std::string& o, const std::string& e, double v) {
    throw std::invalid_argument("carmen: option '" + o + "': expected " + e + ", got " +
                                std::to_string(v));
  };
  if (!(resolution >= 0.005 && resolution <= 5.0))
    bad("--resolution", "a number of metres in [0.005, 5]", resolution);
  if (!(max_range >= 0.0) || !std::isfinite(max_range))
    bad("--max-range", "a number of metres >= 0 (0: the laser's)", max_range);
  if (laser < 0 || laser > 4) bad("--laser", "an integer in [0, 4]", laser);
  if (!(arm_length > 0.0)) bad("--arm-length", "a positive number", arm_length);
  if (!(margin >= 0.0)) bad("margin", "a number >= 0", margin);
}

CarmenResult runCarmen(const CarmenOptions& o) {
  o.validate();
  CarmenRobotConfig robot_config;
  robot_config.laser = o.laser;
  CarmenLogRobot robot(readCarmenLog(o.log), robot_config);
  RobotInterface& iface = robot;  // the core sees only the robot interface

  // Every scan, as the radial maps the core maps from.
  RangeScanConfig scan_config;
  scan_config.max_range = o.max_range;
  std::vector<RadialMap> scans;
  scans.reserve(static_cast<size_t>(robot.scanCount()));
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(kInf);
  Eigen::Vector2d hi = Eigen::Vector2d::Constant(-kInf);
  while (const std::optional<RangeScan> scan = iface.captureScan()) {
    RadialMap m = radialMapFromScan(*scan, scan_config);
    const Eigen::Vector2d origin = m.odometry * m.sensor_origin;
    lo = lo.cwiseMin(origin);
    hi = hi.cwiseMax(origin);
    for (const RadialReading& r : m.readings) {
      if (r.kind == RadialKind::kNone) continue;
      const double a = m.odometry.theta + r.bearing;
      const Eigen::Vector2d end = origin + r.range * Eigen::Vector2d(std::cos(a), std::sin(a));
      lo = lo.cwiseMin(end);
      hi = hi.cwiseMax(end);
    }
    scans.push_back(std::move(m));
  }

  CarmenResult result;
  result.laser = robot.laser();
  result.scans = static_cast<int>(scans.size());
  result.duration_s = scans.back().stamp - scans.front().stamp;
  result.odometry = robot.odometryTrack();
  result.ground_truth = robot.groundTruth();
  for (size_t i = 1; i < result.odometry.size(); ++i)
    result.path_length_m +=
        (result.odometry[i].pose.translation() - result.odometry[i - 1].pose.translation()).norm();

  // The map covers everything the scans reach, aligned to whole cells.
  const double res = o.resolution;
  lo = ((lo.array() - o.margin) / res).floor() * res;
  hi = ((hi.array() + o.margin) / res).ceil() * res;
  const Eigen::Vector2d extent = (hi - lo) / res;
  const double cells = extent.prod();
  if (!mapSizeProblem(std::round(extent.x()), std::round(extent.y())).empty())
    throw std::runtime_error(o.log + ": the map would span " + std::to_string(hi.x() - lo.x()) +
                             " x " + std::to_string(hi.y() - lo.y()) + " m (" +
                             std::to_string(static_cast<long long>(cells)) +
                             " cells): limit the laser's range with --max-range or use a "
                             "coarser --resolution");
  // A laser's sigma (about 1 cm) is below half a cell: each return marks the cells within
  // half a cell of it along the ray occupied, the grid's default.
  result.grid.emplace(MapLimits::covering(lo, hi, res), OccupancyConfig{});
  for (const RadialMap& m : scans) result.grid->insert(m, m.odometry);
  scans.clear();
  const MapLimits& lim = result.grid->limits();
  for (int iy = 0; iy < lim.height; ++iy)
    for (int ix = 0; ix < lim.width; ++ix) {
      const CellState s = result.grid->state(ix, iy);
      result.occupied_cells += s == CellState::kOccupied;
      result.free_cells += s == CellState::kFree;
    }

  CornersOptions corners;
  corners.arm_length = o.arm_length;
  result.corners = findCorners(classifyCells(*result.grid), o.log, corners);

  if (!o.out_dir.empty()) {
    std::vector<TrajectoryOverlay> overlays;
    if (!result.ground_truth.empty()) overlays.push_back({result.ground_truth, 0, 160, 0});
    overlays.push_back({result.odometry, 0, 0, 255});
    const int scale = std::clamp(1200 / std::max(lim.width, lim.height), 1, 3);
    const std::string png = encodeMapPng(*result.grid, overlays, scale);
    std::filesystem::create_directories(o.out_dir);
    writeRosMap(*result.grid, o.out_dir, "map");
    writeFileAtomic(o.out_dir + "/map.png", png);
    writeCorners(result.corners, o.out_dir);
    writeTum(o.out_dir + "/trajectory_odometry.tum", result.odometry, "odometry of " + o.log);
    if (!result.ground_truth.empty())
      writeTum(o.out_dir + "/trajectory_groundtruth.tum", result.ground_truth,
               "ground truth (TRUEPOS) of " + o.log);
  }
  return result;
}

}  // namespace coopmap
