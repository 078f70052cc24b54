#include "sim/world/ground_truth.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace coopmap::sim {

HomeBaseDesign homeBaseInWorld(const World& world) {
  const HomeBaseSpec& hb = world.home_base;
  if (hb.corners.size() != 2)
    throw std::invalid_argument("world '" + world.name + "' has no home base");
  HomeBaseDesign d;
  d.corners.first.position = hb.corners[0].position;
  d.corners.first.heading = hb.corners[0].heading;
  d.corners.second.position = hb.corners[1].position;
  d.corners.second.heading = hb.corners[1].heading;
  d.arm_length = hb.arm_length;
  d.thickness = hb.thickness;
  return d;
}

Pose2 mapFrameInWorld(const World& world, const HomeBaseDesign& design) {
  const HomeBaseDesign built = homeBaseInWorld(world);
  const Corner &w1 = built.corners.first, &w2 = built.corners.second;
  const Corner &m1 = design.corners.first, &m2 = design.corners.second;
  const Eigen::Vector2d dw = w2.position - w1.position, dm = m2.position - m1.position;
  auto differs = [&](const std::string& what) {
    throw std::invalid_argument("the home base of world '" + world.name + "' (" + world.file +
                                ") is not built as the robots' design says: " + what);
  };
  if (std::abs(dw.norm() - dm.norm()) > 0.01)
    differs("its corners are " + std::to_string(dw.norm()) + " m apart, the design's " +
            std::to_string(dm.norm()) + " m");
  if (std::abs(built.arm_length - design.arm_length) > 0.01 ||
      std::abs(built.thickness - design.thickness) > 0.005)
    differs("arms " + std::to_string(built.arm_length) + " m long and " +
            std::to_string(built.thickness) + " m thick, the design's " +
            std::to_string(design.arm_length) + " m and " + std::to_string(design.thickness) +
            " m");
  const double turn = wrapAngle(std::atan2(dw.y(), dw.x()) - std::atan2(dm.y(), dm.x()));
  constexpr double kDegree = M_PI / 180.0;
  if (std::abs(wrapAngle(w1.heading - m1.heading - turn)) > kDegree ||
      std::abs(wrapAngle(w2.heading - m2.heading - turn)) > kDegree)
    differs("its corners face otherwise relative to the line joining them");
  const Pose2 rotate(0.0, 0.0, turn);
  const Eigen::Vector2d t =
      0.5 * (w1.position + w2.position) - rotate * (0.5 * (m1.position + m2.position));
  return Pose2(t.x(), t.y(), turn);
}

MapLimits worldMapLimits(const World& world, double margin, const Pose2& X_WM) {
  const Pose2 X_MW = X_WM.inverse();
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (double x : {world.floor_min.x() - margin, world.floor_max.x() + margin})
    for (double y : {world.floor_min.y() - margin, world.floor_max.y() + margin}) {
      const Eigen::Vector2d p = X_MW * Eigen::Vector2d(x, y);
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  // Corners a rounding error past a whole cell count as on it.
  const double r = world.map_resolution;
  for (int k = 0; k < 2; ++k) {
    lo[k] = std::floor(lo[k] / r + 1e-9) * r;
    hi[k] = std::ceil(hi[k] / r - 1e-9) * r;
  }
  return MapLimits::covering(lo, hi, r);
}

bool insideFootprint(const SolidBox& box, const Eigen::Vector2d& p) {
  const Eigen::Vector2d d = p - box.center;
  const double c = std::cos(box.yaw), s = std::sin(box.yaw);
  const double along = c * d.x() + s * d.y(), across = -s * d.x() + c * d.y();
  return std::abs(along) <= 0.5 * box.size.x() && std::abs(across) <= 0.5 * box.size.y();
}

GridU8 floorMask(const World& world, const MapLimits& limits, const Pose2& X_WM) {
  GridU8 mask(limits, 0);
  const std::vector<FloorArea> rects = world.floorRects();
  for (int iy = 0; iy < limits.height; ++iy)
    for (int ix = 0; ix < limits.width; ++ix) {
      const Eigen::Vector2d c = X_WM * limits.cellCenter(ix, iy);
      mask.at(ix, iy) = std::any_of(rects.begin(), rects.end(), [&](const FloorArea& a) {
        return c.x() > a.min.x() && c.y() > a.min.y() && c.x() < a.max.x() && c.y() < a.max.y();
      });
    }
  return mask;
}

namespace {
// `boxes` in the world; the grid in the map frame at X_WM.
void rasterise(GridU8& truth, const std::vector<SolidBox>& boxes, double max_height,
               const Pose2& X_WM) {
  const MapLimits& limits = truth.limits;
  constexpr int kSub = 4;
  const Pose2 X_MW = X_WM.inverse();
  for (SolidBox box : boxes) {
    box.center = X_MW * box.center;
    box.yaw += X_MW.theta;
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

GridU8 trueOccupancy(const World& world, const MapLimits& limits, double max_height,
                     const Pose2& X_WM) {
  GridU8 truth(limits, 0);
  rasterise(truth, world.solids(), max_height, X_WM);
  return truth;
}

GridU8 trueOccupancyAt(const World& world, const MapLimits& limits, double max_height, double t,
                       const std::vector<Eigen::Vector2d>& people, const Pose2& X_WM) {
  if (people.size() != world.people.size())
    throw std::invalid_argument("trueOccupancyAt: " + std::to_string(people.size()) +
                                " person positions for the world's " +
                                std::to_string(world.people.size()) + " people");
  GridU8 truth = trueOccupancy(world, limits, max_height, X_WM);
  rasterise(truth, world.doorsClosedAt(t), max_height, X_WM);
  const Pose2 X_MW = X_WM.inverse();
  for (size_t k = 0; k < people.size(); ++k) {
    const Eigen::Vector2d c = X_MW * people[k];
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
