// Grid geometry shared by occupancy grids, ground truth and metrics.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace coopmap {

// Cell (ix, iy) covers [origin + (ix, iy) * resolution, origin + (ix+1, iy+1) * resolution);
// iy grows with world y (the PGM writer flips rows so north is up).
struct MapLimits {
  double resolution = 0.05;          // m per cell
  Eigen::Vector2d origin{0.0, 0.0};  // world position of cell (0, 0)'s lower-left corner
  int width = 0;                     // cells along x
  int height = 0;                    // cells along y

  // Limits covering the world rectangle [min, max] at a resolution.
  static MapLimits covering(const Eigen::Vector2d& min, const Eigen::Vector2d& max,
                            double resolution) {
    MapLimits l;
    l.resolution = resolution;
    l.origin = min;
    l.width = static_cast<int>(std::ceil((max.x() - min.x()) / resolution));
    l.height = static_cast<int>(std::ceil((max.y() - min.y()) / resolution));
    return l;
  }
  bool contains(int ix, int iy) const { return ix >= 0 && iy >= 0 && ix < width && iy < height; }
  int cellX(double x) const { return static_cast<int>(std::floor((x - origin.x()) / resolution)); }
  int cellY(double y) const { return static_cast<int>(std::floor((y - origin.y()) / resolution)); }
  Eigen::Vector2d cellCenter(int ix, int iy) const {
    return origin + Eigen::Vector2d(ix + 0.5, iy + 0.5) * resolution;
  }
  size_t index(int ix, int iy) const { return static_cast<size_t>(iy) * width + ix; }
  size_t size() const { return static_cast<size_t>(width) * height; }
};

// The largest grid coopmap makes: 8192 x 8192 cells (409.6 m square at 5 cm; about 200 MB
// per occupancy grid). Every size read from input (a world's floor, a recording's or an agent
// configuration's map, a map image, a log's extent at a resolution) is checked against it
// before anything is allocated.
inline constexpr double kMaxMapCells = 8192.0 * 8192.0;

// "" when a grid of `width` x `height` cells is within kMaxMapCells, else what was found and
// what is allowed (for an error naming the field). Doubles, so that no product overflows.
inline std::string mapSizeProblem(double width, double height) {
  if (width >= 1.0 && height >= 1.0 && width * height <= kMaxMapCells) return "";
  return "a grid of at most 8192 x 8192 = 67108864 cells, got " +
         std::to_string(static_cast<long long>(std::min(width, 1e15))) + " x " +
         std::to_string(static_cast<long long>(std::min(height, 1e15))) + " cells";
}

// A flat row-major grid of small values over MapLimits.
template <typename T>
struct Grid {
  MapLimits limits;
  std::vector<T> cells;

  Grid() = default;
  Grid(const MapLimits& l, T fill) : limits(l), cells(l.size(), fill) {}
  T& at(int ix, int iy) { return cells[limits.index(ix, iy)]; }
  const T& at(int ix, int iy) const { return cells[limits.index(ix, iy)]; }
};

using GridU8 = Grid<uint8_t>;

}  // namespace coopmap
