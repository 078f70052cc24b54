#include "sim/world/world_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace coopmap::sim {

namespace {

std::string at(const Eigen::Vector2d& p) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "(%.2f, %.2f)", p.x(), p.y());
  return buf;
}

// Whether the segment a-b passes through the box's footprint, sampled every 1 cm.
bool segmentHits(const SolidBox& box, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const double length = (b - a).norm();
  const int steps = std::max(1, static_cast<int>(std::ceil(length / 0.01)));
  for (int i = 0; i <= steps; ++i)
    if (distanceToFootprint(box, a + (b - a) * (static_cast<double>(i) / steps)) <= 0.0)
      return true;
  return false;
}

}  // namespace

double distanceToFootprint(const SolidBox& box, const Eigen::Vector2d& p) {
  const Eigen::Vector2d d = p - box.center;
  const double c = std::cos(box.yaw), s = std::sin(box.yaw);
  const double lx = c * d.x() + s * d.y(), ly = -s * d.x() + c * d.y();
  const double ex = std::max(0.0, std::abs(lx) - 0.5 * box.size.x());
  const double ey = std::max(0.0, std::abs(ly) - 0.5 * box.size.y());
  return std::hypot(ex, ey);
}

WorldCheckResult checkWorldExplorable(const World& world, const WorldCheckLimits& limits) {
  const std::vector<SolidBox> solids = world.solids();
  const double keep = limits.robot_radius + limits.start_clearance;

  for (const RobotSpec& r : world.robots) {
    const Eigen::Vector2d p = r.start.translation();
    if (!world.onFloor(p))
      return {WorldCheckStatus::kStartBlocked, r.name + "'s start " + at(p) + " is off the floor"};
    for (const SolidBox& s : solids)
      if (distanceToFootprint(s, p) < keep)
        return {WorldCheckStatus::kStartBlocked, r.name + "'s start " + at(p) + " is within " +
                                                     std::to_string(keep) + " m of a " + s.kind};
  }
  for (size_t i = 0; i < world.robots.size(); ++i)
    for (size_t j = i + 1; j < world.robots.size(); ++j)
      if ((world.robots[i].start.translation() - world.robots[j].start.translation()).norm() <
          limits.min_start_separation)
        return {WorldCheckStatus::kStartsTooClose,
                world.robots[i].name + " and " + world.robots[j].name + " start too close"};

  const auto& corners = world.home_base.corners;
  if (corners.size() == 2) {
    const Eigen::Vector2d middle = 0.5 * (corners[0].position + corners[1].position);
    for (const RobotSpec& r : world.robots) {
      const Eigen::Vector2d p = r.start.translation();
      const double d = (p - middle).norm();
      if (d < limits.min_home_distance || d > limits.max_home_distance)
        return {WorldCheckStatus::kHomeBaseDistance,
                r.name + "'s start is " + std::to_string(d) + " m from the home base"};
    }
    // The solids of each corner: home-base solids come two per corner, in corner order.
    std::vector<int> corner_of(solids.size(), -1);
    int arm = 0;
    for (size_t i = 0; i < solids.size(); ++i)
      if (solids[i].kind == "home_base") corner_of[i] = arm++ / 2;
    const double half = limits.view_half_angle_deg * M_PI / 180.0;
    for (const RobotSpec& r : world.robots) {
      const Eigen::Vector2d p = r.start.translation();
      for (int c = 0; c < 2; ++c) {
        const Eigen::Vector2d v = corners[c].position;
        const Eigen::Vector2d to_start = (p - v).normalized();
        const Eigen::Vector2d heading(std::cos(corners[c].heading), std::sin(corners[c].heading));
        if (to_start.dot(heading) < std::cos(half))
          return {WorldCheckStatus::kHomeBaseHidden, r.name + "'s start " + at(p) +
                                                         " is outside the opening of corner " +
                                                         std::to_string(c + 1)};
        // Up to just inside the vertex: the vertex lies on its own corner's arms.
        const Eigen::Vector2d target = v + 0.06 * heading;
        for (size_t i = 0; i < solids.size(); ++i)
          if (corner_of[i] != c && segmentHits(solids[i], p, target))
            return {WorldCheckStatus::kHomeBaseHidden,
                    "a " + solids[i].kind + " at " + at(solids[i].center) + " hides corner " +
                        std::to_string(c + 1) + " from " + r.name + "'s start"};
      }
    }
  }

  // Reachability: cells of the floor farther than radius + margin from every solid, flood
  // filled (4-connected) from the starts.
  const double cell = limits.cell, inflate = limits.robot_radius + limits.margin;
  const Eigen::Vector2d origin = world.floor_min;
  const int w = static_cast<int>(std::ceil((world.floor_max.x() - origin.x()) / cell));
  const int h = static_cast<int>(std::ceil((world.floor_max.y() - origin.y()) / cell));
  auto centre = [&](int i, int j) {
    return Eigen::Vector2d(origin.x() + (i + 0.5) * cell, origin.y() + (j + 0.5) * cell);
  };
  // 0 blocked, 1 free, 2 reached.
  std::vector<uint8_t> grid(static_cast<size_t>(w) * h, 0);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) grid[static_cast<size_t>(j) * w + i] = world.onFloor(centre(i, j));
  for (const SolidBox& s : solids) {
    const double reach = 0.5 * s.size.head<2>().norm() + inflate;
    const int i0 = std::max(0, static_cast<int>((s.center.x() - reach - origin.x()) / cell));
    const int i1 = std::min(w - 1, static_cast<int>((s.center.x() + reach - origin.x()) / cell));
    const int j0 = std::max(0, static_cast<int>((s.center.y() - reach - origin.y()) / cell));
    const int j1 = std::min(h - 1, static_cast<int>((s.center.y() + reach - origin.y()) / cell));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i)
        if (distanceToFootprint(s, centre(i, j)) <= inflate)
          grid[static_cast<size_t>(j) * w + i] = 0;
  }
  std::vector<int> stack;
  for (const RobotSpec& r : world.robots) {
    const Eigen::Vector2d p = r.start.translation();
    const int i = static_cast<int>((p.x() - origin.x()) / cell);
    const int j = static_cast<int>((p.y() - origin.y()) / cell);
    if (i < 0 || j < 0 || i >= w || j >= h || grid[static_cast<size_t>(j) * w + i] != 1) continue;
    grid[static_cast<size_t>(j) * w + i] = 2;
    stack.push_back(j * w + i);
  }
  while (!stack.empty()) {
    const int k = stack.back();
    stack.pop_back();
    const int i = k % w, j = k / w;
    const int next[4][2] = {{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}};
    for (const auto& n : next) {
      if (n[0] < 0 || n[1] < 0 || n[0] >= w || n[1] >= h) continue;
      uint8_t& g = grid[static_cast<size_t>(n[1]) * w + n[0]];
      if (g == 1) {
        g = 2;
        stack.push_back(n[1] * w + n[0]);
      }
    }
  }
  int unreached = 0;
  Eigen::Vector2d first(0.0, 0.0);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      if (grid[static_cast<size_t>(j) * w + i] == 1 && unreached++ == 0) first = centre(i, j);
  if (unreached > 0)
    return {WorldCheckStatus::kUnreachableFloor,
            std::to_string(unreached) + " free floor cells unreachable from the starts, e.g. at " +
                at(first)};
  return {};
}

}  // namespace coopmap::sim
