// Map files: ROS map_server (NAME.pgm + NAME.yaml) and a colour PNG for people.
#pragma once

#include <string>
#include <vector>

#include "core/io/tum.h"
#include "core/mapping/occupancy_grid.h"

namespace coopmap {

// Writes DIR/NAME.pgm and DIR/NAME.yaml (map_server format, negate 0, thresholds from the
// grid's config), each atomically.
void writeRosMap(const OccupancyGrid& grid, const std::string& dir, const std::string& name);

// Renders the map in colour: free white, occupied black, unknown grey, with trajectories
// drawn over it (each with its BGR colour), north up, `scale` pixels per cell.
struct TrajectoryOverlay {
  std::vector<StampedPose2> poses;
  unsigned char b = 0, g = 0, r = 255;
};
std::string encodeMapPng(const OccupancyGrid& grid, const std::vector<TrajectoryOverlay>& overlays,
                         int scale = 3);

// Renders the map against the true occupancy (same limits), for people: black = wall found,
// red = true wall next to seen free space with no occupied map cell within 1 cell,
// blue = occupied in the map but free in truth, white = seen free, grey = unseen; with
// `drivable`, cells off it (which the metrics do not score) are drawn in bluish greys.
std::string encodeEvaluationPng(const OccupancyGrid& grid, const GridU8& truth, int scale = 3,
                                const GridU8* drivable = nullptr);

// Writes the colour PNG atomically.
void writeMapPng(const std::string& path, const OccupancyGrid& grid,
                 const std::vector<TrajectoryOverlay>& overlays, int scale = 3);

}  // namespace coopmap
