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

#include <vector>

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
  double max_shift_m = 0.1;  // a match that moves the later points farther is refused
  void validate() const;     // throws std::invalid_argument naming the field
};

// Each pair's over-count (odometry displacement over stereo displacement, minus one) with
// its match's 1-sigma, pooled over traverses. The scale is a Huber M-estimate weighting each
// pair by its match's variance plus a spread between pairs estimated from the pairs
// themselves: on rendered stereo the pairs scatter by about 3 % where their matches claim a
// few tenths of one (viewpoint-dependent surfaces, matches to the wrong face), and weights
// from the matches alone let a few pairs decide the figure (measured:
// docs/experiments/2026-12-07-stereo-scale-estimator.md).
struct StereoScale {
  struct Pair {
    double over_count = 0.0;
    double sigma = 0.0;  // of the over-count, from the match's information
  };
  std::vector<Pair> pairs_measured;
  int pairs() const { return static_cast<int>(pairs_measured.size()); }
  void add(const StereoScale& other);
  // k: the fraction by which the odometry over-counts the distance (0 without pairs). Huber
  // weights (1.345) on each pair's variance sigma^2 + tau^2, tau the spread at which the
  // pairs' standardised residuals have a unit normal's median absolute value.
  double scale() const;
};

// The pairs of one traverse log, each at its entry's odometry.
StereoScale stereoDistanceScale(const TraverseLog& log, const StereoScaleConfig& config = {});

}  // namespace coopmap
