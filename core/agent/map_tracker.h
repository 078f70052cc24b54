// Tracking against the shared map during a sortie (beyond the paper, whose robots steer by
// odometry between home-base fixes): every few radial maps, the latest ones, placed at the
// robot's estimate, are aligned to the shared map the robot imported at its last home visit.
// Where they fit well (most of their obstacle points on the map's obstacles) the estimate
// is corrected by the alignment, a small step at a time. The imported map stays fixed for
// the sortie, so the robot never aligns to what it has just mapped itself (that feeds its
// own drift back), and in territory the map does not know, nothing fits and nothing changes.
// Robot-agnostic: radial maps and poses in, a correction of the estimate out.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "core/geometry/pose2.h"
#include "core/localization/manhattan.h"
#include "core/localization/scan_alignment.h"
#include "core/mapping/occupancy_grid.h"
#include "core/perception/radial_map.h"

namespace coopmap {

struct MapTrackerConfig {
  bool enabled = true;
  int scans = 6;               // radial maps aligned together: the latest ones
  int period = 3;              // align after every this many new radial maps
  double min_inliers = 0.75;   // share of obstacle points on the map's obstacles
  int min_points = 80;         // fewer obstacle points: too little to tell
  double max_step_m = 0.3;     // an alignment moving the estimate farther is not trusted
  double max_step_rad = 0.06;  // rad, likewise
  // The share of a trusted alignment applied at once (1: all of it): a little damping keeps
  // one slightly wrong alignment from jerking the robot's path.
  double gain = 0.7;
  AlignmentConfig alignment;
  void validate() const;  // throws std::invalid_argument naming the field
};

class MapTracker {
 public:
  explicit MapTracker(const MapTrackerConfig& config = {});

  // The map to track against (a copy is kept, with its distance field); replaces the last.
  void setMap(const OccupancyGrid& map);
  bool hasMap() const { return aligner_ != nullptr; }
  const MapTrackerConfig& config() const { return config_; }

  // Called once per new radial map with the latest radial maps, each at the robot's current
  // estimate of where it was taken (map frame, oldest first). Every `period` calls, aligns
  // the last `scans` of them; returns the correction to compose onto the estimate
  // (X_new,old: estimate <- correction * estimate) when the alignment is trusted.
  std::optional<Pose2> update(const std::vector<RadialMap>& latest);

  int aligned() const { return aligned_; }    // alignments tried
  int accepted() const { return accepted_; }  // of them, trusted and applied

 private:
  MapTrackerConfig config_;
  std::unique_ptr<OccupancyGrid> map_;
  std::unique_ptr<ScanAligner> aligner_;
  int calls_ = 0, aligned_ = 0, accepted_ = 0;
};

// Headings from the walls while driving (beyond the paper): in a building whose walls run
// along the map frame's axes, the walls in the latest radial maps, placed at the estimate,
// are turned from the axes by the estimate's heading error (manhattanTurn). Every few radial
// maps the estimate is turned back by a share of that, about the latest pose's position, so
// the heading stays within a fraction of a degree of the truth between home-base fixes
// rather than drifting by degrees. It needs no map: it works in territory nobody has seen.
// Where no straight wall is in view (an open room, a wall off the axes) nothing changes.
struct WallHeadingConfig {
  double gain = 0.0;  // the share of the walls' turn applied at once (0: off; the building: 0.5)
  int scans = 6;      // radial maps whose walls are fitted together: the latest ones
  int period = 3;     // fit after every this many new radial maps
  double max_range = 3.5;  // m: hits farther from the camera are left out
  ManhattanConfig manhattan;
  void validate() const;  // throws std::invalid_argument naming the field
};

class WallHeadingTracker {
 public:
  explicit WallHeadingTracker(const WallHeadingConfig& config = {});

  // Called once per new radial map with the latest radial maps, each at the robot's current
  // estimate of where it was taken (map frame, oldest first). Every `period` calls, fits the
  // walls of the last `scans` of them; returns the correction to compose onto the estimate
  // (estimate <- correction * estimate: a turn about the latest pose's position) when they
  // hold walls along the axes.
  std::optional<Pose2> update(const std::vector<RadialMap>& latest);

  bool enabled() const { return config_.gain > 0.0; }
  const WallHeadingConfig& config() const { return config_; }
  int fitted() const { return fitted_; }  // fits tried
  int turned() const { return turned_; }  // of them, with walls: the estimate turned

 private:
  WallHeadingConfig config_;
  int calls_ = 0, fitted_ = 0, turned_ = 0;
};

}  // namespace coopmap
