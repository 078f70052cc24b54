#include "core/agent/obstacle_memory.h"

#include <algorithm>
#include <iterator>
#include <unordered_map>
#include <utility>

#include "core/agent/mission_maps.h"

namespace coopmap {

namespace {

// Sets every cell of `grid` whose centre lies within `radius` of `p` to `value`.
template <typename T>
void fillDisc(Grid<T>& grid, const Eigen::Vector2d& p, double radius, T value) {
  const MapLimits& lim = grid.limits;
  const int n = static_cast<int>(std::ceil(radius / lim.resolution));
  const int cx = lim.cellX(p.x()), cy = lim.cellY(p.y());
  for (int iy = cy - n; iy <= cy + n; ++iy)
    for (int ix = cx - n; ix <= cx + n; ++ix)
      if (lim.contains(ix, iy) && (lim.cellCenter(ix, iy) - p).norm() <= radius)
        grid.at(ix, iy) = value;
}

}  // namespace

ObstacleMemory::ObstacleMemory(const MissionConfig& config) : config_(config) {}

void ObstacleMemory::markVisited(const OccupancyGrid& map, const Pose2& odometry) {
  const MapLimits& lim = map.limits();
  if (visited_.cells.empty()) visited_ = GridU8(lim, 0);
  const double r =
      config_.visited_radius > 0.0 ? config_.visited_radius : config_.planning.robot_radius;
  fillDisc(visited_, odometry.translation(), r, uint8_t{1});
  if (config_.trail_after_waits > 0) {
    if (trail_.cells.empty()) trail_ = GridU8(lim, 0);
    // Wide enough that a path along it keeps the least margin (homing) from what lies beyond.
    fillDisc(trail_, odometry.translation(),
             config_.planning.robot_radius + leastMargin(lim) + lim.resolution, uint8_t{1});
  }
}

size_t ObstacleMemory::rememberHits(double now, const Pose2& odometry, const RadialMap& scan) {
  if (!(config_.recent_hits_s > 0.0)) return 0;
  const double since = now - config_.recent_hits_s;
  size_t old = 0;
  while (old < recent_.size() && recent_[old].t < since) ++old;
  recent_.erase(recent_.begin(), recent_.begin() + static_cast<std::ptrdiff_t>(old));
  sensor_origin_ = scan.sensor_origin;
  markSeenThrough(odometry, scan);
  const size_t before = recent_.size();
  ++recent_frames_;
  for (const RadialReading& r : scan.readings)
    if (r.kind == RadialKind::kHit && r.range <= config_.recent_hits_range)
      recent_.push_back(
          {now, recent_frames_,
           odometry * (scan.sensor_origin +
                       r.range * Eigen::Vector2d(std::cos(r.bearing), std::sin(r.bearing))),
           false});
  return recent_.size() - before;
}

void ObstacleMemory::addBump(const Pose2& odometry, double bearing) {
  // The bumper found what the map missed (too low, too thin, or drift put it elsewhere): an
  // obstacle where the robot touched it, in the frame of its estimate like its map. A bumper
  // does not say how far an edge goes on either side: the touch is spread across the bearing.
  const double edge = config_.planning.robot_radius + 0.5 * config_.bump_radius;
  const Eigen::Vector2d at(std::cos(bearing), std::sin(bearing));
  const Eigen::Vector2d across(-at.y(), at.x());
  const int n = static_cast<int>(std::ceil(0.5 * config_.bump_width / config_.bump_radius));
  for (int k = -n; k <= n; ++k) {
    const double s =
        std::clamp(k * config_.bump_radius, -0.5 * config_.bump_width, 0.5 * config_.bump_width);
    bumps_.push_back(odometry * Eigen::Vector2d(edge * at + s * across));
  }
}

void ObstacleMemory::markSeenThrough(const Pose2& odometry, const RadialMap& scan) {
  // Past a hit by more than this (m) in its column: the hit's place is seen free. Wider than
  // stereo's range noise at the 2 m the hits are kept within.
  constexpr double kPast = 0.15;
  const std::vector<RadialReading>& cols = scan.readings;
  if (cols.size() < 2) return;
  // One reading per image column: bearings run monotonically, left to right (decreasing) in
  // a camera's, either way in other scans.
  const bool descending = cols.front().bearing > cols.back().bearing;
  const double column = std::abs(cols[1].bearing - cols[0].bearing);
  const Eigen::Vector2d cameras = odometry * scan.sensor_origin;
  for (RecentHit& h : recent_) {
    if (h.seen_through) continue;
    const Eigen::Vector2d to = h.p - cameras;
    const double bearing = std::remainder(std::atan2(to.y(), to.x()) - odometry.theta, 2.0 * M_PI);
    const auto after = std::lower_bound(cols.begin(), cols.end(), bearing,
                                        [descending](const RadialReading& r, double b) {
                                          return descending ? r.bearing > b : r.bearing < b;
                                        });
    const RadialReading* nearest = after == cols.end() ? &cols.back() : &*after;
    if (after != cols.begin() &&
        std::abs(std::prev(after)->bearing - bearing) < std::abs(nearest->bearing - bearing))
      nearest = &*std::prev(after);
    if (std::abs(nearest->bearing - bearing) > column) continue;  // out of view
    h.seen_through = (nearest->kind == RadialKind::kHit || nearest->kind == RadialKind::kBeyond) &&
                     nearest->range > to.norm() + kPast;
  }
}

bool ObstacleMemory::recentHitAhead(const Pose2& odometry, double distance,
                                    double half_angle) const {
  const Eigen::Vector2d cameras = odometry * sensor_origin_;
  for (const RecentHit& h : recent_) {
    const Eigen::Vector2d to = h.p - cameras;
    if (!h.seen_through && to.norm() < distance &&
        std::abs(std::remainder(std::atan2(to.y(), to.x()) - odometry.theta, 2.0 * M_PI)) <
            half_angle)
      return true;
  }
  return false;
}

bool ObstacleMemory::freshHitNear(const std::vector<Eigen::Vector2d>& way, size_t fresh) const {
  if (fresh == 0) return false;
  // The planning map's clearance, and a cell's diagonal for where in its cell a hit lies.
  const double reach = config_.planning.robot_radius + config_.planning.margin + 0.1;
  for (size_t k = recent_.size() - fresh; k < recent_.size(); ++k)
    if (nearWay(way, recent_[k].p, reach)) return true;
  return false;
}

PlanningMap ObstacleMemory::planningMap(const OccupancyGrid& map, const Eigen::Vector2d& robot,
                                        const std::vector<Eigen::Vector2d>& teammates,
                                        const PlanningMapOptions& options) const {
  // Where the robot has been is free though the cameras never saw it (they never see beneath
  // the robot), or saw a weak obstacle there (a stereo mismatch). Not where they saw an
  // obstacle again and again: the estimate drifts, so "where it has been" can lie on a table
  // it saw a minute ago.
  // With a narrow visited strip, the whole footprint where the robot stands now (the planner
  // starts there).
  const MapLimits& lim = map.limits();
  const bool trail = options.trail;
  const double footprint =
      config_.visited_radius > 0.0 && config_.visited_radius < config_.planning.robot_radius
          ? config_.planning.robot_radius
          : 0.0;
  Grid<CellState> states(lim, CellState::kUnknown);
  for (int iy = 0; iy < lim.height; ++iy)
    for (int ix = 0; ix < lim.width; ++ix) {
      const CellState seen = map.state(ix, iy);
      const bool visited = (!visited_.cells.empty() && visited_.at(ix, iy)) ||
                           (footprint > 0.0 && (lim.cellCenter(ix, iy) - robot).squaredNorm() <=
                                                   footprint * footprint);
      const bool firm =
          seen == CellState::kOccupied && map.logOdds(ix, iy) >= config_.firm_log_odds;
      const bool on_trail = trail && !trail_.cells.empty() && trail_.at(ix, iy);
      states.at(ix, iy) = on_trail || (visited && !firm) ? CellState::kFree : seen;
    }
  // What the cameras saw a moment ago, where the robot's estimate put it then.
  if (options.recent) {
    const double keep_out =
        config_.planning.robot_radius + config_.planning.margin + 2.0 * lim.resolution;
    // cell -> (the last frame that saw it, how many frames did)
    std::unordered_map<size_t, std::pair<int, int>> seen_by;
    for (const RecentHit& h : recent_) {
      const int ix = lim.cellX(h.p.x()), iy = lim.cellY(h.p.y());
      if (!lim.contains(ix, iy)) continue;
      const double d = (lim.cellCenter(ix, iy) - robot).norm();
      if (d <= keep_out || d > config_.recent_hits_range) continue;
      if (trail && !trail_.cells.empty() && trail_.at(ix, iy)) continue;  // trail_after_waits
      auto& [frame, frames] = seen_by[lim.index(ix, iy)];
      if (frame != h.frame) {
        frame = h.frame;
        if (++frames == config_.recent_hits_support) states.at(ix, iy) = CellState::kOccupied;
      }
    }
  }
  // What the bumpers touched this sortie, and teammates while they stand where they are.
  for (const Eigen::Vector2d& p : bumps_)
    fillDisc(states, p, config_.bump_radius, CellState::kOccupied);
  PlanningMapConfig c = config_.planning;
  c.allow_unknown = options.allow_unknown;
  if (options.margin >= 0.0) c.margin = options.margin;
  // A teammate standing nearer than its disc and this robot's clearance (two robots placed
  // side by side, one coming back to the home base beside the other) leaves free the cells
  // the robot's own clearance needs where it stands: else both stand on blocked cells and
  // neither can plan a step away. The rest of the disc stands, so the only ways out lead
  // away from the teammate.
  const double own_clearance = c.robot_radius + c.margin + lim.resolution;
  for (const Eigen::Vector2d& p : teammates) {
    const MapLimits& l = states.limits;
    const int n = static_cast<int>(std::ceil(config_.team_radius / l.resolution));
    const int cx = l.cellX(p.x()), cy = l.cellY(p.y());
    for (int iy = cy - n; iy <= cy + n; ++iy)
      for (int ix = cx - n; ix <= cx + n; ++ix) {
        if (!l.contains(ix, iy)) continue;
        const Eigen::Vector2d cell = l.cellCenter(ix, iy);
        if ((cell - p).norm() <= config_.team_radius && (cell - robot).norm() > own_clearance)
          states.at(ix, iy) = CellState::kOccupied;
      }
  }
  return PlanningMap(states, c);
}

void ObstacleMemory::startSortie() {
  bumps_.clear();
  trail_ = GridU8{};
  recent_.clear();
}

void ObstacleMemory::clear() {
  bumps_.clear();
  recent_.clear();
  visited_ = GridU8{};
  trail_ = GridU8{};
}

}  // namespace coopmap
