#include "core/agent/mission_maps.h"

#include <algorithm>
#include <cmath>

namespace coopmap {

std::optional<Eigen::Vector2d> nearestFreeCell(const PlanningMap& planning,
                                               const Eigen::Vector2d& from, double within) {
  const MapLimits& lim = planning.limits();
  const int n = static_cast<int>(std::ceil(within / lim.resolution));
  const int cx = lim.cellX(from.x()), cy = lim.cellY(from.y());
  double best = 1e300;
  std::optional<Eigen::Vector2d> to;
  for (int iy = cy - n; iy <= cy + n; ++iy)
    for (int ix = cx - n; ix <= cx + n; ++ix) {
      const Eigen::Vector2d c = lim.cellCenter(ix, iy);
      const double d = (c - from).norm();
      if (d < best && d <= within && planning.free(ix, iy) && planning.segmentFree(c, c)) {
        best = d;
        to = c;
      }
    }
  return to;
}

Waypoint ontoCell(const Eigen::Vector2d& centre, double resolution) {
  Waypoint wp{centre, false, 0.0, 0.0};
  wp.arrive_tolerance = 0.25 * resolution;
  return wp;
}

std::optional<Eigen::Vector2d> nearestReachable(const PlanningMap& planning,
                                                const Eigen::Vector2d& from,
                                                const Eigen::Vector2d& to) {
  const MapLimits& lim = planning.limits();
  const int region = planning.region(lim.cellX(from.x()), lim.cellY(from.y()));
  if (region == 0) return std::nullopt;
  const double start = (to - from).norm();
  double best = start - 0.5;  // worth going only if it is at least 0.5 m nearer
  std::optional<Eigen::Vector2d> out;
  for (int iy = 0; iy < lim.height; ++iy)
    for (int ix = 0; ix < lim.width; ++ix) {
      if (planning.region(ix, iy) != region) continue;
      const Eigen::Vector2d c = lim.cellCenter(ix, iy);
      const double d = (c - to).norm();
      if (d < best) {
        best = d;
        out = c;
      }
    }
  return out;
}

bool nearWay(const std::vector<Eigen::Vector2d>& way, const Eigen::Vector2d& p, double within) {
  for (size_t k = 0; k + 1 < way.size(); ++k) {
    const Eigen::Vector2d a = way[k], ab = way[k + 1] - a;
    const double t =
        ab.squaredNorm() > 0.0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
    if ((a + t * ab - p).norm() < within) return true;
  }
  return false;
}

std::vector<Waypoint> routeAlong(const std::vector<Eigen::Vector2d>& waypoints) {
  std::vector<Waypoint> route;
  for (size_t i = 1; i < waypoints.size(); ++i) route.push_back({waypoints[i], false, 0.0, 0.0});
  return route;
}

}  // namespace coopmap
