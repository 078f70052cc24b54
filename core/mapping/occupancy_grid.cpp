#include "core/mapping/occupancy_grid.h"

#include <algorithm>
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

void OccupancyGrid::insert(const RadialMap& scan, const Pose2& X_WR) {
  const MapLimits& lim = log_odds_.limits;
  if (++scan_id_ == 0) {  // wrapped: reset stamps
    std::fill(stamp_.begin(), stamp_.end(), 0);
    scan_id_ = 1;
  }
  touched_.clear();
  const Eigen::Vector2d origin = X_WR * scan.sensor_origin;
  const double res = lim.resolution;

  for (const RadialReading& reading : scan.readings) {
    if (reading.kind == RadialKind::kNone) continue;
    const bool hit = reading.kind == RadialKind::kHit;
    const double half_width =
        hit ? std::max(0.5 * res + config_.min_half_width, config_.sigma_scale * reading.sigma)
            : 0.0;
    const double t_end = hit ? reading.range + half_width : reading.range;
    // The evidence of one return is spread over its uncertainty region: a far, uncertain
    // return adds less occupancy per cell than a near, sharp one.
    const double peak = hit ? config_.occupied_delta * std::min(1.0, res / half_width) : 0.0;
    const double a = X_WR.theta + reading.bearing;
    const double dx = std::cos(a), dy = std::sin(a);

    // Amanatides-Woo traversal of the cells the ray crosses, from the sensor outwards.
    int ix = lim.cellX(origin.x()), iy = lim.cellY(origin.y());
    const int step_x = dx > 0 ? 1 : -1, step_y = dy > 0 ? 1 : -1;
    const double inf = std::numeric_limits<double>::infinity();
    const double next_x = lim.origin.x() + (ix + (step_x > 0 ? 1 : 0)) * res;
    const double next_y = lim.origin.y() + (iy + (step_y > 0 ? 1 : 0)) * res;
    double t_max_x = dx != 0.0 ? (next_x - origin.x()) / dx : inf;
    double t_max_y = dy != 0.0 ? (next_y - origin.y()) / dy : inf;
    const double t_delta_x = dx != 0.0 ? res / std::abs(dx) : inf;
    const double t_delta_y = dy != 0.0 ? res / std::abs(dy) : inf;
    double t = 0.0;
    while (t < t_end) {
      if (!lim.contains(ix, iy)) break;
      const Eigen::Vector2d c = lim.cellCenter(ix, iy) - origin;
      const double s = c.x() * dx + c.y() * dy;  // distance of the cell centre along the ray
      int delta = config_.free_delta;
      if (hit && s >= reading.range - half_width) {
        const double w = 1.0 - std::abs(s - reading.range) / half_width;
        delta = std::max(1, static_cast<int>(std::lround(peak * std::max(0.25, w))));
      } else if (!hit && s > reading.range) {
        break;
      }
      // Cells up to the measured surface were observed; those behind it only get evidence.
      touch(lim.index(ix, iy), delta, !hit || s <= reading.range + 0.5 * res);
      if (t_max_x < t_max_y) {
        t = t_max_x;
        t_max_x += t_delta_x;
        ix += step_x;
      } else {
        t = t_max_y;
        t_max_y += t_delta_y;
        iy += step_y;
      }
    }
  }
  const int lo = -config_.clamp, hi = config_.clamp;
  for (size_t cell : touched_) {
    log_odds_.cells[cell] =
        static_cast<int16_t>(std::clamp(log_odds_.cells[cell] + pending_[cell], lo, hi));
    if (pending_seen_[cell]) seen_.cells[cell] = 1;
  }
}

}  // namespace coopmap
