// `coopmap corners MAP.yaml`: corner landmarks of any ROS map_server map, as a picture
// (edges and fitted corners over the map) and a JSON list.
#pragma once

#include <string>

#include "core/landmarks/corner_detector.h"

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
};

// Throws ConfigError for a bad map file, std::runtime_error when outputs cannot be written.
CornersResult runCorners(const CornersOptions& options);

}  // namespace coopmap
