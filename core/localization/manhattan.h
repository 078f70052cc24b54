// Beyond the paper: a heading from the building's walls. In a Manhattan world (walls along
// two perpendicular axes, as most buildings' corridors are) the walls a robot sees tell its
// heading modulo 90 degrees, absolutely, wherever it is: a few degrees of drift show as walls
// turned from the axes. The turn that makes the points' histograms along the axes sharpest
// (the walls fall into the fewest bins), searched within a window small enough that no other
// wall direction is taken for an axis, finds the walls; a line fitted to each wall then
// gives the turn, the walls weighted by how well their lines are known.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

namespace coopmap {

struct ManhattanConfig {
  double axes_rad = 0.0;            // direction of the building's axes in the map frame
  double search_rad = 0.05;         // the turns searched: +-search_rad
  double step_rad = 0.0025;         // their spacing
  double bin_m = 0.05;              // histogram bins along each axis
  int min_points = 150;             // fewer obstacle points give no estimate
  double min_sharpness_gain = 1.1;  // best score over the window's median score, at least
  int min_wall_points = 30;         // points near a wall, at least
  int min_wall_samples = 8;         // bins along a wall with points, at least
  double min_wall_m = 0.5;          // length of a wall, at least
  double max_gap_m = 0.2;           // a longer stretch without points ends a wall
  void validate() const;            // throws std::invalid_argument naming the field
};

struct ManhattanFit {
  double turn_rad = 0.0;  // the points are turned by this from the axes (turn them back by it)
  double gain = 0.0;      // best score over the median score
  int points = 0;
  int walls = 0;  // walls whose lines gave the turn
};

// The turn of `points` (map frame) from the building's axes; nothing when there are too few
// points, the histograms are no sharper at any turn than at most (no straight walls), the
// sharpest turn is at the window's edge (walls of another direction), or no wall is long
// and straight enough for a line (min_wall_samples bins over min_wall_m).
std::optional<ManhattanFit> manhattanTurn(const std::vector<Eigen::Vector2d>& points,
                                          const ManhattanConfig& config = {});

}  // namespace coopmap
