// Log-odds occupancy grid (Moravec-Elfes) with a "seen" layer, updated from radial maps.
#pragma once

#include <cstdint>
#include <vector>

#include "core/geometry/pose2.h"
#include "core/mapping/grid.h"
#include "core/perception/radial_map.h"

namespace coopmap {

enum class CellState : uint8_t { kUnknown = 0, kFree = 1, kOccupied = 2 };

// Log-odds are stored in hundredths (int16): 100 = log-odds 1.0.
struct OccupancyConfig {
  int free_delta = -40;         // per scan, for a cell the ray passes through
  int occupied_delta = 90;      // per scan, peak, for a cell at the measured range
  int clamp = 1000;             // |log-odds| limit, keeps the map able to change
  int occupied_threshold = 60;  // log-odds above this: occupied
  int free_threshold = -60;     // log-odds below this: free
  double min_half_width = 0.0;  // m; extra to the half-cell the uncertainty region always has
  double sigma_scale = 1.0;     // uncertainty half-width = sigma_scale * range sigma

  void validate() const;  // throws std::invalid_argument naming the field
  bool operator==(const OccupancyConfig&) const = default;
};

class OccupancyGrid {
 public:
  OccupancyGrid(const MapLimits& limits, const OccupancyConfig& config);

  // Inserts a radial map seen from robot pose X_WR (the map's frame): cells along each
  // column's ray are made freer, cells within the range uncertainty more occupied. A
  // cell is updated at most once per scan, occupied winning over free. Cells up to the
  // measured surface become "seen"; cells behind it get evidence but stay unseen.
  void insert(const RadialMap& scan, const Pose2& X_WR);

  const MapLimits& limits() const { return log_odds_.limits; }
  int16_t logOdds(int ix, int iy) const { return log_odds_.at(ix, iy); }
  bool seen(int ix, int iy) const { return seen_.at(ix, iy) != 0; }
  CellState state(int ix, int iy) const;
  const Grid<int16_t>& logOddsGrid() const { return log_odds_; }
  const GridU8& seenGrid() const { return seen_; }
  const OccupancyConfig& config() const { return config_; }
  // Occupancy probability of a cell (0.5 when unseen).
  double probability(int ix, int iy) const;
  // Replaces both layers (e.g. restoring a saved map); throws std::invalid_argument when
  // the sizes differ from the grid's.
  void assign(const std::vector<int16_t>& log_odds, const std::vector<uint8_t>& seen);

 private:
  void touch(size_t cell, int delta, bool observed);

  OccupancyConfig config_;
  Grid<int16_t> log_odds_;
  GridU8 seen_;
  std::vector<uint32_t> stamp_;        // scan id that last touched a cell
  std::vector<int16_t> pending_;       // this scan's delta per touched cell
  std::vector<uint8_t> pending_seen_;  // this scan observed the cell (not only behind a hit)
  std::vector<size_t> touched_;
  uint32_t scan_id_ = 0;
};

}  // namespace coopmap
