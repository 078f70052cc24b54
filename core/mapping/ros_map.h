// Reading ROS map_server maps (NAME.yaml + image) into cell classes for the landmark code.
#pragma once

#include <string>

#include "core/landmarks/corner_detector.h"
#include "core/mapping/grid.h"

namespace coopmap {

struct RosMap {
  GridU8 classes;     // CellClass per cell; row iy = 0 is the image's bottom row
  std::string image;  // resolved image path
  double occupied_thresh = 0.65, free_thresh = 0.196;
  bool negate = false;
};

// Loads a map_server YAML and its image. Errors (ConfigError) name the file, line and
// field; an unreadable image names the image file. Cells darker than occupied_thresh are
// occupied, lighter than free_thresh free, 205 (map_saver's unknown) unknown, the rest
// uncertain.
RosMap loadRosMap(const std::string& yaml_path);

}  // namespace coopmap
