#include "core/mapping/map_metrics.h"

#include <stdexcept>
#include <vector>

#include <opencv2/core/mat.hpp>
#include <opencv2/imgproc.hpp>

namespace coopmap {

GridU8 reachableFree(const GridU8& truth, const Eigen::Vector2d& start, const GridU8* drivable) {
  const MapLimits& lim = truth.limits;
  GridU8 reach(lim, 0);
  auto open = [&](int x, int y) {
    return truth.at(x, y) == 0 && (!drivable || drivable->at(x, y) != 0);
  };
  const int sx = lim.cellX(start.x()), sy = lim.cellY(start.y());
  if (!lim.contains(sx, sy) || !open(sx, sy)) return reach;
  std::vector<std::pair<int, int>> stack{{sx, sy}};
  reach.at(sx, sy) = 1;
  while (!stack.empty()) {
    const auto [x, y] = stack.back();
    stack.pop_back();
    const int nx[4] = {x + 1, x - 1, x, x};
    const int ny[4] = {y, y, y + 1, y - 1};
    for (int k = 0; k < 4; ++k) {
      if (!lim.contains(nx[k], ny[k]) || !open(nx[k], ny[k]) || reach.at(nx[k], ny[k])) continue;
      reach.at(nx[k], ny[k]) = 1;
      stack.push_back({nx[k], ny[k]});
    }
  }
  return reach;
}

MapMetrics computeMapMetrics(const OccupancyGrid& map, const GridU8& truth,
                             const Eigen::Vector2d& start, const GridU8* drivable) {
  const MapLimits& lim = map.limits();
  if (truth.limits.width != lim.width || truth.limits.height != lim.height ||
      truth.limits.resolution != lim.resolution || truth.limits.origin != lim.origin)
    throw std::invalid_argument("computeMapMetrics: truth and map limits differ");
  auto neighbourhood = [&](int x, int y, auto&& pred) {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (lim.contains(x + dx, y + dy) && pred(x + dx, y + dy)) return true;
    return false;
  };
  MapMetrics m;
  int wall_hits = 0, false_occ = 0, covered = 0;
  std::array<int, MapMetrics::kDistanceBands> false_by_band{};
  const GridU8 reach = reachableFree(truth, start, drivable);
  // Chessboard distance (cells) of every cell to the nearest true obstacle: 1 for the
  // 8-neighbourhood of one.
  cv::Mat not_obstacle(lim.height, lim.width, CV_8U), to_obstacle;
  for (int y = 0; y < lim.height; ++y)
    for (int x = 0; x < lim.width; ++x) not_obstacle.at<uint8_t>(y, x) = truth.at(x, y) ? 0 : 255;
  cv::distanceTransform(not_obstacle, to_obstacle, cv::DIST_C, 3);
  auto band = [](float d) {
    return d < 2.5f ? 0 : d < 3.5f ? 1 : d < 5.5f ? 2 : d < 10.5f ? 3 : 4;
  };
  for (int y = 0; y < lim.height; ++y) {
    for (int x = 0; x < lim.width; ++x) {
      if (truth.at(x, y)) {
        const bool next_to_observed_free = neighbourhood(x, y, [&](int a, int b) {
          return truth.at(a, b) == 0 && map.seen(a, b) && (!drivable || drivable->at(a, b));
        });
        if (!next_to_observed_free) continue;
        ++m.wall_cells;
        if (neighbourhood(x, y,
                          [&](int a, int b) { return map.state(a, b) == CellState::kOccupied; }))
          ++wall_hits;
        continue;
      }
      if (reach.at(x, y)) {
        ++m.reachable_cells;
        if (map.seen(x, y)) ++covered;
      }
      if (!map.seen(x, y) || (drivable && !drivable->at(x, y))) continue;
      // More than one cell from any true obstacle: none in the 8-neighbourhood.
      const float to_true = to_obstacle.at<float>(y, x);
      if (to_true < 1.5f) continue;
      ++m.clear_observed_cells;
      if (map.state(x, y) == CellState::kOccupied) {
        ++false_occ;
        ++false_by_band[band(to_true)];
      }
    }
  }
  m.wall_recall = m.wall_cells ? static_cast<double>(wall_hits) / m.wall_cells : 0.0;
  m.false_occupied_rate =
      m.clear_observed_cells ? static_cast<double>(false_occ) / m.clear_observed_cells : 0.0;
  for (int b = 0; b < MapMetrics::kDistanceBands; ++b)
    m.false_occupied_by_distance[b] =
        m.clear_observed_cells ? static_cast<double>(false_by_band[b]) / m.clear_observed_cells
                               : 0.0;
  m.coverage = m.reachable_cells ? static_cast<double>(covered) / m.reachable_cells : 0.0;
  return m;
}

}  // namespace coopmap
