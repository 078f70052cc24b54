#include "core/planning/blockage_look.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>

namespace coopmap {

namespace {

// Price per metre of crossing a cell, against 1 for a cell the robot may stand in: a cell
// known free but too near obstacles for the robot (a narrow doorway), or observed too little
// to tell, is a small price; an occupied one a large one, so that the way found squeezes
// through a narrowed opening before it crosses a wall. Never-observed cells are no way.
constexpr double kNarrowPrice = 4.0;
constexpr double kOccupiedPrice = 25.0;
constexpr double kNoWay = -1.0;

double priceOf(const OccupancyGrid& grid, const PlanningMap& planning, int ix, int iy) {
  if (planning.free(ix, iy)) return 1.0;
  const CellState state = grid.state(ix, iy);
  if (state == CellState::kOccupied) return kOccupiedPrice;
  if (state == CellState::kUnknown && !grid.seen(ix, iy)) return kNoWay;
  return kNarrowPrice;
}

// Dijkstra over 8-connected cells from `start`: each cell's cost and the cell it is reached
// from (-1 for the start and cells not reached).
struct Ways {
  std::vector<double> cost;
  std::vector<int64_t> from;
};

Ways cheapestWays(const OccupancyGrid& grid, const PlanningMap& planning, int sx, int sy) {
  const MapLimits& lim = grid.limits();
  Ways w;
  w.cost.assign(lim.size(), std::numeric_limits<double>::infinity());
  w.from.assign(lim.size(), -1);
  using Item = std::pair<double, int64_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  const int64_t start = static_cast<int64_t>(lim.index(sx, sy));
  w.cost[start] = 0.0;
  open.push({0.0, start});
  while (!open.empty()) {
    const auto [c, i] = open.top();
    open.pop();
    if (c > w.cost[i]) continue;
    const int x = static_cast<int>(i % lim.width), y = static_cast<int>(i / lim.width);
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        if (dx == 0 && dy == 0) continue;
        const int jx = x + dx, jy = y + dy;
        if (!lim.contains(jx, jy)) continue;
        const double price = priceOf(grid, planning, jx, jy);
        if (price == kNoWay) continue;
        const int64_t j = static_cast<int64_t>(lim.index(jx, jy));
        const double next = c + price * lim.resolution * std::hypot(dx, dy);
        if (next < w.cost[j]) {
          w.cost[j] = next;
          w.from[j] = i;
          open.push({next, j});
        }
      }
  }
  return w;
}

// Whether the segment a -> b crosses no occupied cell before coming within `short_of` of b
// (the blockage's own cells).
bool sightOf(const OccupancyGrid& grid, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
             double short_of) {
  const MapLimits& lim = grid.limits();
  const double length = (b - a).norm();
  const double step = lim.resolution * 0.5;
  for (double s = 0.0; s < length - short_of; s += step) {
    const Eigen::Vector2d p = a + (b - a) * (s / length);
    const int ix = lim.cellX(p.x()), iy = lim.cellY(p.y());
    if (lim.contains(ix, iy) && grid.state(ix, iy) == CellState::kOccupied) return false;
  }
  return true;
}

}  // namespace

std::optional<BlockageLook> findBlockageLook(const OccupancyGrid& grid, const PlanningMap& planning,
                                             const Eigen::Vector2d& robot,
                                             const std::vector<Frontier>& frontiers,
                                             const std::vector<Eigen::Vector2d>& looked,
                                             double skip_radius) {
  const MapLimits& lim = grid.limits();
  const int rx = lim.cellX(robot.x()), ry = lim.cellY(robot.y());
  const int region = planning.region(rx, ry);
  if (region == 0) return std::nullopt;
  std::vector<const Frontier*> by_gain;
  for (const Frontier& f : frontiers)
    if (f.gain > 0) by_gain.push_back(&f);
  if (by_gain.empty()) return std::nullopt;
  std::stable_sort(by_gain.begin(), by_gain.end(),
                   [](const Frontier* a, const Frontier* b) { return a->gain > b->gain; });
  const Ways ways = cheapestWays(grid, planning, rx, ry);
  for (const Frontier* f : by_gain) {
    int64_t end = -1;
    for (const Eigen::Vector2d& c : f->cells) {
      const int ix = lim.cellX(c.x()), iy = lim.cellY(c.y());
      if (!lim.contains(ix, iy)) continue;
      const int64_t i = static_cast<int64_t>(lim.index(ix, iy));
      if (std::isfinite(ways.cost[i]) && (end < 0 || ways.cost[i] < ways.cost[end])) end = i;
    }
    if (end < 0) continue;             // beyond never-observed cells only
    std::vector<Eigen::Vector2d> way;  // robot first
    std::vector<bool> in_region;
    std::vector<bool> standable;
    for (int64_t i = end; i >= 0; i = ways.from[i]) {
      const int ix = static_cast<int>(i % lim.width), iy = static_cast<int>(i / lim.width);
      way.push_back(lim.cellCenter(ix, iy));
      in_region.push_back(planning.region(ix, iy) == region);
      standable.push_back(planning.free(ix, iy));
    }
    std::reverse(way.begin(), way.end());
    std::reverse(in_region.begin(), in_region.end());
    std::reverse(standable.begin(), standable.end());
    const auto leave = std::find(in_region.begin(), in_region.end(), false);
    if (leave == in_region.begin() || leave == in_region.end()) continue;  // nothing closes it
    const size_t enter = static_cast<size_t>(leave - in_region.begin());
    // The blockage: from where the way leaves the region to where the robot could stand
    // again (or the frontier), its middle, no farther than a metre in.
    size_t beyond = enter;
    while (beyond < way.size() && !standable[beyond]) ++beyond;
    // With nowhere to stand beyond it, a stretch no longer than the robot's clearance either
    // side is the frontier's own: the unknown beyond it is what keeps the robot off.
    const double clearance = planning.config().robot_radius + planning.config().margin;
    if (beyond == way.size() && (way.back() - way[enter]).norm() <= 2.0 * clearance) continue;
    size_t middle = enter + (beyond - enter) / 2;
    while (middle > enter && (way[middle] - way[enter]).norm() > 1.0) --middle;
    const Eigen::Vector2d at = way[middle];
    const bool seen_before = std::any_of(looked.begin(), looked.end(), [&](const auto& p) {
      return (p - at).norm() <= skip_radius;
    });
    if (seen_before) continue;
    // From: back along the way, the first cell far enough and in sight of the blockage (the
    // robot's own cell when none is).
    const double into = (at - way[enter]).norm() + 3.0 * lim.resolution;
    size_t from = 0;
    for (size_t k = enter; k-- > 0;)
      if ((way[k] - at).norm() >= kBlockageLookDistance && sightOf(grid, way[k], at, into)) {
        from = k;
        break;
      }
    BlockageLook look;
    look.from = from == 0 ? robot : way[from];
    look.at = at;
    look.heading = std::atan2(at.y() - look.from.y(), at.x() - look.from.x());
    look.frontier = f->centroid;
    return look;
  }
  return std::nullopt;
}

}  // namespace coopmap
