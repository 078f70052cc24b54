// Shared by the planning tests: literal and random maps, and checks of planned paths that do
// not trust the code under test (a brute-force inflation, dense sampling, a grid search).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <queue>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/pose2.h"
#include "core/mapping/grid.h"
#include "core/mapping/occupancy_grid.h"
#include "core/planning/planning_map.h"
#include "core/robot/robot_interface.h"

namespace coopmap::planning_test {

// Rows from north (top, highest iy) to south: '.' free, '#' occupied, '?' unknown.
inline Grid<CellState> parse(const std::vector<std::string>& rows, double resolution) {
  MapLimits l;
  l.resolution = resolution;
  l.width = static_cast<int>(rows.front().size());
  l.height = static_cast<int>(rows.size());
  Grid<CellState> g(l, CellState::kFree);
  for (int iy = 0; iy < l.height; ++iy) {
    const std::string& row = rows[static_cast<size_t>(l.height - 1 - iy)];
    for (int ix = 0; ix < l.width; ++ix)
      g.at(ix, iy) = row[static_cast<size_t>(ix)] == '#'   ? CellState::kOccupied
                     : row[static_cast<size_t>(ix)] == '?' ? CellState::kUnknown
                                                           : CellState::kFree;
  }
  return g;
}

// 'o' free for the robot, 'x' not, rows from north as in parse().
inline std::vector<std::string> render(const PlanningMap& m) {
  std::vector<std::string> rows;
  for (int iy = m.limits().height - 1; iy >= 0; --iy) {
    std::string row;
    for (int ix = 0; ix < m.limits().width; ++ix) row += m.free(ix, iy) ? 'o' : 'x';
    rows.push_back(row);
  }
  return rows;
}

// The inflation recomputed by brute force, independent of PlanningMap: a cell is free when
// its centre is farther than radius + margin from the centre of every blocked cell and of
// every cell outside the map.
inline std::vector<uint8_t> bruteFree(const Grid<CellState>& g, const PlanningMapConfig& c) {
  const MapLimits& l = g.limits;
  const double need = (c.robot_radius + c.margin) / l.resolution;
  const int reach = static_cast<int>(std::ceil(need)) + 1;
  std::vector<uint8_t> out(l.size(), 0);
  for (int iy = 0; iy < l.height; ++iy)
    for (int ix = 0; ix < l.width; ++ix) {
      bool ok = true;
      for (int dy = -reach; dy <= reach && ok; ++dy)
        for (int dx = -reach; dx <= reach && ok; ++dx) {
          if (std::hypot(dx, dy) > need) continue;
          const int jx = ix + dx, jy = iy + dy;
          const bool blocked = !l.contains(jx, jy) || g.at(jx, jy) == CellState::kOccupied ||
                               (g.at(jx, jy) == CellState::kUnknown && !c.allow_unknown);
          if (blocked) ok = false;
        }
      out[l.index(ix, iy)] = ok;
    }
  return out;
}

// Samples every segment at a quarter cell (and its end): all samples in brute-force free
// cells. Returns the first offending point's description, or "" when clean.
inline std::string denseCheck(const std::vector<Eigen::Vector2d>& w, const MapLimits& l,
                              const std::vector<uint8_t>& free) {
  if (w.size() < 2) return "fewer than two waypoints";
  for (size_t i = 0; i + 1 < w.size(); ++i) {
    const double len = (w[i + 1] - w[i]).norm();
    const int n = std::max(1, static_cast<int>(std::ceil(len / (l.resolution / 4.0))));
    for (int k = 0; k <= n; ++k) {
      const Eigen::Vector2d p = w[i] + (w[i + 1] - w[i]) * (static_cast<double>(k) / n);
      const int ix = static_cast<int>(std::floor((p.x() - l.origin.x()) / l.resolution));
      const int iy = static_cast<int>(std::floor((p.y() - l.origin.y()) / l.resolution));
      if (!l.contains(ix, iy) || !free[l.index(ix, iy)])
        return "segment " + std::to_string(i) + " sample " + std::to_string(k) + " in cell (" +
               std::to_string(ix) + ", " + std::to_string(iy) + ")";
    }
  }
  return "";
}

// Is the goal cell reachable from the start cell through 4-connected brute-force free cells?
inline bool bfsReachable(const MapLimits& l, const std::vector<uint8_t>& free,
                         const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const int ax = l.cellX(a.x()), ay = l.cellY(a.y()), bx = l.cellX(b.x()), by = l.cellY(b.y());
  if (!l.contains(ax, ay) || !free[l.index(ax, ay)]) return false;
  std::vector<uint8_t> seen(l.size(), 0);
  std::queue<std::pair<int, int>> q;
  q.push({ax, ay});
  seen[l.index(ax, ay)] = 1;
  while (!q.empty()) {
    const auto [x, y] = q.front();
    q.pop();
    if (x == bx && y == by) return true;
    const int nx[4] = {x + 1, x - 1, x, x}, ny[4] = {y, y, y + 1, y - 1};
    for (int k = 0; k < 4; ++k)
      if (l.contains(nx[k], ny[k]) && free[l.index(nx[k], ny[k])] && !seen[l.index(nx[k], ny[k])]) {
        seen[l.index(nx[k], ny[k])] = 1;
        q.push({nx[k], ny[k]});
      }
  }
  return false;
}

// Drives the commands from a pose: turns in place, straights along the heading.
inline Pose2 drive(Pose2 p, const std::vector<MotionCommand>& commands) {
  for (const MotionCommand& c : commands) {
    if (c.kind == MotionCommand::Kind::kTurn) p.theta = wrapAngle(p.theta + c.amount);
    if (c.kind == MotionCommand::Kind::kStraight) {
      p.x += c.amount * std::cos(p.theta);
      p.y += c.amount * std::sin(p.theta);
    }
  }
  return p;
}

// Literal maps at 10 cm for a robot of radius 10 cm and no margin: a cell is free for it
// when no blocked cell is a 4-neighbour.
inline PlanningMapConfig smallRobot() {
  PlanningMapConfig c;
  c.robot_radius = 0.1;
  c.margin = 0.0;
  return c;
}

// 80 x 80 cells at 5 cm (4 m x 4 m): random furniture boxes and a few unknown patches.
inline Grid<CellState> randomMap(uint32_t seed) {
  std::mt19937 rng(seed);
  MapLimits l;
  l.width = l.height = 80;
  Grid<CellState> g(l, CellState::kFree);
  std::uniform_int_distribution<int> pos(0, 79), size(2, 16), kind(0, 4);
  for (int k = 0; k < 12; ++k) {
    const int x0 = pos(rng), y0 = pos(rng), w = size(rng), h = size(rng);
    const CellState s = kind(rng) == 0 ? CellState::kUnknown : CellState::kOccupied;
    for (int iy = y0; iy < std::min(80, y0 + h); ++iy)
      for (int ix = x0; ix < std::min(80, x0 + w); ++ix) g.at(ix, iy) = s;
  }
  return g;
}

// A random point in a brute-force free cell, somewhere inside the cell.
inline Eigen::Vector2d randomFreePoint(std::mt19937& rng, const MapLimits& l,
                                       const std::vector<uint8_t>& free) {
  std::uniform_int_distribution<int> cx(0, l.width - 1), cy(0, l.height - 1);
  std::uniform_real_distribution<double> off(0.05, 0.95);
  for (;;) {
    const int ix = cx(rng), iy = cy(rng);
    if (free[l.index(ix, iy)])
      return l.origin + Eigen::Vector2d(ix + off(rng), iy + off(rng)) * l.resolution;
  }
}

}  // namespace coopmap::planning_test
