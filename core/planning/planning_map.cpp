#include "core/planning/planning_map.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/robot/robot_interface.h"

namespace coopmap {
namespace {

Grid<CellState> statesOf(const OccupancyGrid& grid) {
  Grid<CellState> s(grid.limits(), CellState::kUnknown);
  for (int iy = 0; iy < s.limits.height; ++iy)
    for (int ix = 0; ix < s.limits.width; ++ix) s.at(ix, iy) = grid.state(ix, iy);
  return s;
}

}  // namespace

PlanningMapConfig PlanningMapConfig::forRobot(const RobotDescription& robot) {
  PlanningMapConfig c;
  c.robot_radius = robot.body_radius;
  return c;
}

void PlanningMapConfig::validate() const {
  auto bad = [](const std::string& f, const std::string& e, double v) {
    throw std::invalid_argument("planning map config: field '" + f + "': expected " + e + ", got " +
                                std::to_string(v));
  };
  if (!(robot_radius > 0.0 && robot_radius <= 5.0))
    bad("robot_radius", "a radius in (0, 5] m", robot_radius);
  if (!(margin >= 0.0 && margin <= 5.0)) bad("margin", "a margin in [0, 5] m", margin);
}

PlanningMap::PlanningMap(const OccupancyGrid& grid, const PlanningMapConfig& config)
    : PlanningMap(statesOf(grid), config) {}

PlanningMap::PlanningMap(const Grid<CellState>& states, const PlanningMapConfig& config)
    : config_(config), limits_(states.limits) {
  config_.validate();
  if (limits_.width <= 0 || limits_.height <= 0 || !(limits_.resolution > 0.0))
    throw std::invalid_argument("PlanningMap: limits must have positive size and resolution");
  if (states.cells.size() != limits_.size())
    throw std::invalid_argument("PlanningMap: " + std::to_string(states.cells.size()) +
                                " cells for a " + std::to_string(limits_.width) + " x " +
                                std::to_string(limits_.height) + " grid");
  blocked_ = GridU8(limits_, 0);
  for (size_t i = 0; i < states.cells.size(); ++i) {
    const CellState s = states.cells[i];
    blocked_.cells[i] =
        s == CellState::kOccupied || (s == CellState::kUnknown && !config_.allow_unknown);
  }
  build();
}

void PlanningMap::build() {
  const int w = limits_.width, h = limits_.height;
  // A ring of blocked cells around the map: the outside is not known to be free.
  cv::Mat open(h + 2, w + 2, CV_8UC1, cv::Scalar(0));
  for (int iy = 0; iy < h; ++iy) {
    uint8_t* row = open.ptr<uint8_t>(iy + 1) + 1;
    for (int ix = 0; ix < w; ++ix) row[ix] = blocked_.at(ix, iy) ? 0 : 255;
  }
  cv::Mat dist;  // cells from each open cell's centre to the nearest blocked cell's centre
  cv::distanceTransform(open, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);

  const double needed = (config_.robot_radius + config_.margin) / limits_.resolution;
  clearance_ = Grid<float>(limits_, 0.0f);
  free_ = GridU8(limits_, 0);
  cv::Mat free_mask(h, w, CV_8UC1, cv::Scalar(0));
  for (int iy = 0; iy < h; ++iy) {
    const float* d = dist.ptr<float>(iy + 1) + 1;
    uint8_t* m = free_mask.ptr<uint8_t>(iy);
    for (int ix = 0; ix < w; ++ix) {
      clearance_.at(ix, iy) = static_cast<float>(d[ix] * limits_.resolution);
      const bool ok = d[ix] > needed;
      free_.at(ix, iy) = ok;
      m[ix] = ok ? 255 : 0;
    }
  }
  cv::Mat labels;
  cv::connectedComponents(free_mask, labels, 4, CV_32S);
  region_ = Grid<int32_t>(limits_, 0);
  for (int iy = 0; iy < h; ++iy) {
    const int32_t* l = labels.ptr<int32_t>(iy);
    std::copy(l, l + w, region_.cells.begin() + static_cast<std::ptrdiff_t>(limits_.index(0, iy)));
  }
}

bool PlanningMap::connected(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const {
  const int ra = region(limits_.cellX(a.x()), limits_.cellY(a.y()));
  return ra != 0 && ra == region(limits_.cellX(b.x()), limits_.cellY(b.y()));
}

// Walks the cells the segment crosses (Amanatides-Woo) in continuous cell coordinates.
// Where it passes through a cell corner (within a tolerance) both cells beside the corner
// are checked too, so a segment never slips diagonally between two blocked cells.
std::optional<double> PlanningMap::firstBlockedOnSegment(const Eigen::Vector2d& a,
                                                         const Eigen::Vector2d& b) const {
  const int ax = limits_.cellX(a.x()), ay = limits_.cellY(a.y());
  const int bx = limits_.cellX(b.x()), by = limits_.cellY(b.y());
  if (!free(ax, ay)) return 0.0;
  const Eigen::Vector2d ua = (a - limits_.origin) / limits_.resolution;
  const Eigen::Vector2d d = (b - a) / limits_.resolution;
  const double cells = d.norm();
  const int sx = d.x() > 0 ? 1 : -1, sy = d.y() > 0 ? 1 : -1;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double dx_t = d.x() != 0.0 ? 1.0 / std::abs(d.x()) : kInf;
  const double dy_t = d.y() != 0.0 ? 1.0 / std::abs(d.y()) : kInf;
  int ix = ax, iy = ay;
  double next_x = d.x() != 0.0 ? ((sx > 0 ? ix + 1 : ix) - ua.x()) / d.x() : kInf;
  double next_y = d.y() != 0.0 ? ((sy > 0 ? iy + 1 : iy) - ua.y()) / d.y() : kInf;
  // Corner tolerance: 1e-9 cells along the segment.
  const double tie = cells > 0.0 ? 1e-9 / cells : 0.0;
  const int max_steps = 2 * (std::abs(bx - ax) + std::abs(by - ay)) + 4;
  for (int step = 0; step < max_steps && (ix != bx || iy != by); ++step) {
    const double t = std::min(next_x, next_y);
    // A boundary met at the very end (b on it) is not crossed: no part of the segment lies
    // beyond it. Stepping over it made a segment ending on a cell corner next to a blocked
    // cell blocked, while a longer one through the same corner, of which it is a part, was
    // free.
    if (t >= 1.0 - tie) break;
    if (std::abs(next_x - next_y) <= tie) {
      if (!free(ix + sx, iy) || !free(ix, iy + sy)) return std::max(0.0, t);
      ix += sx;
      iy += sy;
      next_x += dx_t;
      next_y += dy_t;
    } else if (next_x < next_y) {
      ix += sx;
      next_x += dx_t;
    } else {
      iy += sy;
      next_y += dy_t;
    }
    if (!free(ix, iy)) return std::max(0.0, t);
  }
  // The end cell as the world point maps to it (the walk may stop a rounding short of it).
  if (!free(bx, by)) return 1.0;
  return std::nullopt;
}

}  // namespace coopmap
