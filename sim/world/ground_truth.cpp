#include "sim/world/ground_truth.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace coopmap::sim {

MapLimits worldMapLimits(const World& world, double margin) {
  const Eigen::Vector2d m(margin, margin);
  return MapLimits::covering(world.floor_min - m, world.floor_max + m, world.map_resolution);
}

bool insideFootprint(const SolidBox& box, const Eigen::Vector2d& p) {
  const Eigen::Vector2d d = p - box.center;
  const double c = std::cos(box.yaw), s = std::sin(box.yaw);
  const double along = c * d.x() + s * d.y(), across = -s * d.x() + c * d.y();
  return std::abs(along) <= 0.5 * box.size.x() && std::abs(across) <= 0.5 * box.size.y();
}

GridU8 floorMask(const World& world, const MapLimits& limits) {
  GridU8 mask(limits, 0);
  const std::vector<FloorArea> rects = world.floorRects();
  for (int iy = 0; iy < limits.height; ++iy)
    for (int ix = 0; ix < limits.width; ++ix) {
      const Eigen::Vector2d c = limits.cellCenter(ix, iy);
      mask.at(ix, iy) = std::any_of(rects.begin(), rects.end(), [&](const FloorArea& a) {
        return c.x() > a.min.x() && c.y() > a.min.y() && c.x() < a.max.x() && c.y() < a.max.y();
      });
    }
  return mask;
}

namespace {
void rasterise(GridU8& truth, const std::vector<SolidBox>& boxes, double max_height) {
  const MapLimits& limits = truth.limits;
  constexpr int kSub = 4;
  for (const SolidBox& box : boxes) {
    if (box.z0 > max_height || box.z0 + box.size.z() <= 0.0) continue;
    // Bounding rectangle of the rotated footprint.
    const double c = std::abs(std::cos(box.yaw)), s = std::abs(std::sin(box.yaw));
    const double hx = 0.5 * (c * box.size.x() + s * box.size.y());
    const double hy = 0.5 * (s * box.size.x() + c * box.size.y());
    const int x0 = std::max(0, limits.cellX(box.center.x() - hx));
    const int x1 = std::min(limits.width - 1, limits.cellX(box.center.x() + hx));
    const int y0 = std::max(0, limits.cellY(box.center.y() - hy));
    const int y1 = std::min(limits.height - 1, limits.cellY(box.center.y() + hy));
    for (int iy = y0; iy <= y1; ++iy) {
      for (int ix = x0; ix <= x1; ++ix) {
        if (truth.at(ix, iy)) continue;
        for (int k = 0; k < kSub * kSub; ++k) {
          const Eigen::Vector2d p = limits.origin + Eigen::Vector2d(ix + (k % kSub + 0.5) / kSub,
                                                                    iy + (k / kSub + 0.5) / kSub) *
                                                        limits.resolution;
          if (insideFootprint(box, p)) {
            truth.at(ix, iy) = 1;
            break;
          }
        }
      }
    }
  }
}
}  // namespace

GridU8 trueOccupancy(const World& world, const MapLimits& limits, double max_height) {
  GridU8 truth(limits, 0);
  rasterise(truth, world.solids(), max_height);
  return truth;
}

GridU8 trueOccupancyAt(const World& world, const MapLimits& limits, double max_height, double t,
                       const std::vector<Eigen::Vector2d>& people) {
  if (people.size() != world.people.size())
    throw std::invalid_argument("trueOccupancyAt: " + std::to_string(people.size()) +
                                " person positions for the world's " +
                                std::to_string(world.people.size()) + " people");
  GridU8 truth = trueOccupancy(world, limits, max_height);
  rasterise(truth, world.doorsClosedAt(t), max_height);
  for (size_t k = 0; k < people.size(); ++k) {
    const Eigen::Vector2d& c = people[k];
    const double r = world.people[k].radius;
    for (int iy = limits.cellY(c.y() - r); iy <= limits.cellY(c.y() + r); ++iy)
      for (int ix = limits.cellX(c.x() - r); ix <= limits.cellX(c.x() + r); ++ix)
        if (limits.contains(ix, iy) &&
            (limits.cellCenter(ix, iy) - c).norm() <= r + 0.5 * limits.resolution)
          truth.at(ix, iy) = 1;
  }
  return truth;
}

GridU8 trueOccupancyAt(const World& world, const MapLimits& limits, double max_height, double t) {
  std::vector<Eigen::Vector2d> people;
  for (const PersonSpec& p : world.people) people.push_back(p.positionAt(t));
  return trueOccupancyAt(world, limits, max_height, t, people);
}

}  // namespace coopmap::sim
