// The odometry's distance scale measured by the cameras (beyond the paper). A home-base fix
// cannot observe it (an out-and-back path's distance errors cancel), and loop closures to
// a map drawn at the odometry's own scale only confirm it. Stereo ranges are metric: along
// straight stretches of a traverse, the obstacle points of the radial maps around one entry
// are matched to those around an entry 1-1.5 m earlier (point to line: each point against
// the surface through its nearest earlier points, so a wall seen farther on pulls nothing
// along itself), and the displacement along the travel the match finds is compared with
// the odometry's. Only pairs whose surfaces pin the position along the travel (faces across
// it: door jambs, corners, furniture) count.
#pragma once

#include "core/correction/traverse_log.h"

namespace coopmap {

struct StereoScaleConfig {
  double min_gap_m = 1.0;  // odometry distance between the two entries of a pair
  double max_gap_m = 1.5;
  int half_window = 2;           // radial maps either side of each entry (5 per side)
  int step = 1;                  // entries between the first entries of successive pairs
  double max_turn_rad = 0.1;     // summed turn over the pair's span: straight stretches only
  double max_range_m = 3.5;      // farther stereo returns are too noisy
  double match_m = 0.15;         // a point's nearest earlier point, at most this far
  double normal_radius_m = 0.1;  // earlier points this near fit the surface through one
  double max_sigma_m = 0.005;    // 1-sigma of the match's position along the travel, at most
  int max_iterations = 20;
  // Passes, each after the first from the odometry rescaled to the one before's figure:
  // more passes find more of the whole scale, but in the building one pass maps better
  // (measured: docs/experiments/2026-12-building-sessions-25-34.md).
  int passes = 1;
  double max_shift_m = 0.1;  // a match that moves the later points farther is refused
  void validate() const;     // throws std::invalid_argument naming the field
};

// Weighted least squares of odometry displacement d_o against stereo displacement d_s
// (d_o = (1 + k) d_s, weights 1 / sigma^2): sums to pool over traverses.
struct StereoScale {
  double sum_so = 0.0;  // sum w d_s d_o
  double sum_ss = 0.0;  // sum w d_s^2
  int pairs = 0;
  void add(const StereoScale& other);
  // k: the fraction by which the odometry over-counts the distance (0 without pairs).
  double scale() const { return sum_ss > 0.0 ? sum_so / sum_ss - 1.0 : 0.0; }
};

// The matches lean toward the displacement they start from, the odometry's: one pass finds
// only part of a scale (StereoScaleConfig::passes; measured:
// docs/experiments/2026-12-building-settings.md).
StereoScale stereoDistanceScale(const TraverseLog& log, const StereoScaleConfig& config = {});

}  // namespace coopmap
