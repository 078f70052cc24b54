#include "core/mapping/occupancy_grid.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace coopmap {

void OccupancyConfig::validate() const {
  auto bad = [](const std::string& f, const std::string& e, double v) {
    throw std::invalid_argument("occupancy config: field '" + f + "': expected " + e + ", got " +
                                std::to_string(v));
  };
  if (free_delta >= 0 || free_delta < -1000)
    bad("free_delta", "an integer in [-1000, 0)", free_delta);
  if (occupied_delta <= 0 || occupied_delta > 1000)
    bad("occupied_delta", "an integer in (0, 1000]", occupied_delta);
  if (clamp < 100 || clamp > 30000) bad("clamp", "an integer in [100, 30000]", clamp);
  if (occupied_threshold <= 0 || occupied_threshold >= clamp)
    bad("occupied_threshold", "an integer in (0, clamp)", occupied_threshold);
  if (free_threshold >= 0 || free_threshold <= -clamp)
    bad("free_threshold", "an integer in (-clamp, 0)", free_threshold);
  if (!(min_half_width >= 0.0)) bad("min_half_width", "a number >= 0", min_half_width);
  if (!(sigma_scale > 0.0)) bad("sigma_scale", "a positive number", sigma_scale);
}

OccupancyGrid::OccupancyGrid(const MapLimits& limits, const OccupancyConfig& config)
    : config_(config), log_odds_(limits, 0), seen_(limits, 0) {
  config_.validate();
  if (limits.width <= 0 || limits.height <= 0 || !(limits.resolution > 0.0))
    throw std::invalid_argument("OccupancyGrid: limits must have positive size and resolution");
  stamp_.assign(limits.size(), 0);
  pending_.assign(limits.size(), 0);
  pending_seen_.assign(limits.size(), 0);
}

CellState OccupancyGrid::state(int ix, int iy) const {
  if (!seen(ix, iy)) return CellState::kUnknown;
  const int l = logOdds(ix, iy);
  if (l > config_.occupied_threshold) return CellState::kOccupied;
  if (l < config_.free_threshold) return CellState::kFree;
  return CellState::kUnknown;
}

void OccupancyGrid::assign(const std::vector<int16_t>& log_odds, const std::vector<uint8_t>& seen) {
  if (log_odds.size() != log_odds_.cells.size() || seen.size() != seen_.cells.size())
    throw std::invalid_argument("OccupancyGrid::assign: " + std::to_string(log_odds.size()) +
                                " and " + std::to_string(seen.size()) + " cells for a grid of " +
                                std::to_string(log_odds_.cells.size()));
  log_odds_.cells = log_odds;
  seen_.cells = seen;
}

double OccupancyGrid::probability(int ix, int iy) const {
  return 1.0 / (1.0 + std::exp(-logOdds(ix, iy) / 100.0));
}

void OccupancyGrid::touch(size_t cell, int delta, bool observed) {
  if (stamp_[cell] != scan_id_) {
    stamp_[cell] = scan_id_;
    pending_[cell] = static_cast<int16_t>(delta);
    pending_seen_[cell] = observed;
    touched_.push_back(cell);
    return;
  }
  if (delta > pending_[cell]) pending_[cell] = static_cast<int16_t>(delta);  // occupied wins
  pending_seen_[cell] = pending_seen_[cell] || observed;
}

namespace {

// Walks the cells a ray crosses (Amanatides-Woo), from parameter t = 0 at `origin`, calling
// visit(cell index, s) with s the distance of the cell centre along the ray, until visit
// returns false, the ray reaches t_end or leaves the grid. s grows along the walk. With
// t_start, `origin` is the point at that distance along the ray and s counts from there.
// The choice of axis at each step, which the CPU cannot predict, is arithmetic.
template <typename Visit>
void walkRay(const MapLimits& lim, const Eigen::Vector2d& origin, double dx, double dy,
             double t_end, Visit&& visit, double t_start = 0.0) {
  const double res = lim.resolution;
  int ix = lim.cellX(origin.x()), iy = lim.cellY(origin.y());
  const int step_x = dx > 0 ? 1 : -1, step_y = dy > 0 ? 1 : -1;
  const double inf = std::numeric_limits<double>::infinity();
  const double next_x = lim.origin.x() + (ix + (step_x > 0 ? 1 : 0)) * res;
  const double next_y = lim.origin.y() + (iy + (step_y > 0 ? 1 : 0)) * res;
  double t_max_x = dx != 0.0 ? (next_x - origin.x()) / dx : inf;
  double t_max_y = dy != 0.0 ? (next_y - origin.y()) / dy : inf;
  const double t_delta_x = dx != 0.0 ? res / std::abs(dx) : inf;
  const double t_delta_y = dy != 0.0 ? res / std::abs(dy) : inf;
  const Eigen::Vector2d c0 = lim.cellCenter(ix, iy) - origin;
  double s = c0.x() * dx + c0.y() * dy + t_start;
  const double ds_x = step_x * res * dx, ds_y = step_y * res * dy;  // both >= 0
  const unsigned width = static_cast<unsigned>(lim.width);
  const unsigned height = static_cast<unsigned>(lim.height);
  const long step_index_y = static_cast<long>(step_y) * lim.width;
  long index = static_cast<long>(iy) * lim.width + ix;
  double t = 0.0;
  while (t < t_end) {
    if (static_cast<unsigned>(ix) >= width || static_cast<unsigned>(iy) >= height) return;
    if (!visit(static_cast<size_t>(index), s)) return;
    const bool along_x = t_max_x < t_max_y;
    t = along_x ? t_max_x : t_max_y;
    t_max_x += along_x ? t_delta_x : 0.0;
    t_max_y += along_x ? 0.0 : t_delta_y;
    ix += along_x ? step_x : 0;
    iy += along_x ? 0 : step_y;
    index += along_x ? step_x : step_index_y;
    s += along_x ? ds_x : ds_y;
  }
}

}  // namespace

void OccupancyGrid::insert(const RadialMap& scan, const Pose2& X_WR) {
  const MapLimits& lim = log_odds_.limits;
  if (++scan_id_ == 0) {  // wrapped: reset stamps
    std::fill(stamp_.begin(), stamp_.end(), 0);
    scan_id_ = 1;
  }
  touched_.clear();
  const Eigen::Vector2d origin = X_WR * scan.sensor_origin;
  const double res = lim.resolution;
  auto halfWidth = [&](const RadialReading& r) {
    return std::max(0.5 * res + config_.min_half_width, config_.sigma_scale * r.sigma);
  };

  // Pass 1: the uncertainty region of every return (occupied evidence, few cells).
  for (const RadialReading& reading : scan.readings) {
    if (reading.kind != RadialKind::kHit) continue;
    const double half_width = halfWidth(reading);
    // The evidence of one return is spread over its uncertainty region: a far, uncertain
    // return adds less occupancy per cell than a near, sharp one.
    const double peak = config_.occupied_delta * std::min(1.0, res / half_width);
    const double a = X_WR.theta + reading.bearing;
    const double dx = std::cos(a), dy = std::sin(a);
    const double near = reading.range - half_width;
    const double start = std::max(0.0, near - res);  // the walk begins just before the region
    walkRay(
        lim, origin + start * Eigen::Vector2d(dx, dy), dx, dy, reading.range + half_width - start,
        [&](size_t cell, double s) {
          if (s < near) return true;
          const double w = 1.0 - std::abs(s - reading.range) / half_width;
          const int delta = std::max(1, static_cast<int>(std::lround(peak * std::max(0.25, w))));
          // Cells up to the measured surface were observed; those behind it only get evidence.
          touch(cell, delta, s <= reading.range + 0.5 * res);
          return true;
        },
        start);
  }
  // Pass 2: free space up to each return's uncertainty region (or up to the range of a
  // "beyond" column). A cell is updated once per scan and occupied evidence wins, so cells
  // already touched this scan are skipped (but count as observed).
  const int lo = -config_.clamp, hi = config_.clamp;
  const int16_t free_delta = static_cast<int16_t>(config_.free_delta);
  int16_t* log_odds = log_odds_.cells.data();
  uint8_t* seen = seen_.cells.data();
  uint32_t* stamp = stamp_.data();
  auto freeUntil = [&](const RadialReading& r) {
    if (r.kind == RadialKind::kNone) return 0.0;
    return r.kind == RadialKind::kHit ? r.range - halfWidth(r) : r.range;
  };
  // Near the sensor neighbouring rays cross the same cells. Over the columns, a binary
  // hierarchy: a column at level l (2^l divides its index, 2^(l+1) does not) starts its
  // walk where the two coarser columns 2^l to either side have drifted more than 0.7 cell
  // apart, and no farther than they reach; column 0 and the ends walk from the sensor.
  const size_t n = scan.readings.size();
  for (size_t k = 0; k < n; ++k) {
    const RadialReading& reading = scan.readings[k];
    if (reading.kind == RadialKind::kNone) continue;
    const bool hit = reading.kind == RadialKind::kHit;
    const double until = freeUntil(reading);
    double start = 0.0;
    if (k > 0) {
      const size_t step = size_t{1} << std::countr_zero(k);
      if (k + step < n) {
        const RadialReading& left = scan.readings[k - step];
        const RadialReading& right = scan.readings[k + step];
        const double gap = std::abs(right.bearing - left.bearing);
        if (gap > 1e-9) {
          start = std::min({0.7 * res / gap, freeUntil(left), freeUntil(right)});
          start = std::max(0.0, std::min(start, until) - res);
        }
      }
    }
    const double a = X_WR.theta + reading.bearing;
    const double dx = std::cos(a), dy = std::sin(a);
    walkRay(
        lim, origin + start * Eigen::Vector2d(dx, dy), dx, dy, until + res - start,
        [&](size_t cell, double s) {
          if (hit ? s >= until : s > until) return false;
          if (stamp[cell] == scan_id_) {
            pending_seen_[cell] = 1;
            return true;
          }
          stamp[cell] = scan_id_;
          log_odds[cell] = static_cast<int16_t>(std::max(lo, log_odds[cell] + free_delta));
          seen[cell] = 1;
          return true;
        },
        start);
  }
  for (size_t cell : touched_) {
    log_odds[cell] = static_cast<int16_t>(std::clamp(log_odds[cell] + pending_[cell], lo, hi));
    if (pending_seen_[cell]) seen[cell] = 1;
  }
}

}  // namespace coopmap
