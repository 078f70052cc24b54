#include "core/mapping/ros_map.h"

#include <cmath>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>

#include "core/io/image_file.h"
#include "core/io/yaml_reader.h"

namespace coopmap {

RosMap loadRosMap(const std::string& yaml_path) {
  const YamlField root = YamlField::loadFile(yaml_path);
  root.allowOnly(
      {"image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh", "mode"});
  RosMap map;
  const std::filesystem::path image = root["image"].asString();
  map.image = image.is_absolute()
                  ? image.string()
                  : (std::filesystem::path(yaml_path).parent_path() / image).string();
  const double resolution = root["resolution"].asDouble(1e-4, 100.0, "a cell size in m");
  const Eigen::Vector3d origin = root["origin"].asVector3();
  map.negate = root.has("negate") && root["negate"].asInt(0, 1) == 1;
  map.occupied_thresh =
      optionalDouble(root, "occupied_thresh", 0.65, 0.0, 1.0, "a probability in [0, 1]");
  map.free_thresh = optionalDouble(root, "free_thresh", 0.196, 0.0, 1.0, "a probability in [0, 1]");
  if (map.free_thresh >= map.occupied_thresh)
    root["free_thresh"].fail("a probability below occupied_thresh");
  if (std::abs(origin.z()) > 1e-9)
    root["origin"].fail("[x, y, 0] (rotated maps are not supported)");
  cv::Mat img;
  try {
    img = readImage(map.image, cv::IMREAD_GRAYSCALE, kMaxMapCells);
  } catch (const ConfigError& e) {
    throw ConfigError(std::string(e.what()) + " (the map image named in " + yaml_path + ")");
  }

  MapLimits lim;
  lim.resolution = resolution;
  lim.origin = origin.head<2>();
  lim.width = img.cols;
  lim.height = img.rows;
  map.classes = GridU8(lim, static_cast<uint8_t>(CellClass::kUnknown));
  for (int row = 0; row < img.rows; ++row) {
    const int iy = img.rows - 1 - row;  // the image's top row is the map's largest y
    for (int ix = 0; ix < img.cols; ++ix) {
      const int v = img.at<uint8_t>(row, ix);
      if (v == 205) continue;  // map_saver's unknown
      const double p = map.negate ? v / 255.0 : (255 - v) / 255.0;
      map.classes.at(ix, iy) = static_cast<uint8_t>(p > map.occupied_thresh ? CellClass::kOccupied
                                                    : p < map.free_thresh   ? CellClass::kFree
                                                                          : CellClass::kUncertain);
    }
  }
  return map;
}

}  // namespace coopmap
