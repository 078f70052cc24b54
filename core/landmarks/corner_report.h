// `coopmap corners MAP.yaml`: corner landmarks of any ROS map_server map, as a picture
// (edges and fitted corners over the map) and a JSON list.
#pragma once

#include <string>

#include "core/landmarks/corner_detector.h"
#include "core/mapping/grid.h"

namespace coopmap {

struct CornersOptions {
  std::string map_yaml;
  std::string out_dir;      // corners.png and corners.json go here
  double arm_length = 0.6;  // m, each arm of the corner model
  int scale = 0;            // picture pixels per cell; 0 chooses
};

struct CornersResult {
  CornerSearch search;
  int edge_cells = 0;
  std::string png;   // corners.png: edges and fitted corners over the map
  std::string json;  // corners.json
};

// Throws ConfigError for a bad map file, std::runtime_error when outputs cannot be written.
CornersResult runCorners(const CornersOptions& options);

// Finds the corners of a classified grid (CellClass per cell) and renders corners.png and
// corners.json (`source` names the map in the JSON); writes nothing. options.map_yaml and
// options.out_dir are not used.
CornersResult findCorners(const GridU8& classes, const std::string& source,
                          const CornersOptions& options);

// Writes corners.png and corners.json of a result to a folder (created if missing), each
// atomically.
void writeCorners(const CornersResult& result, const std::string& out_dir);

}  // namespace coopmap
