#include "core/landmarks/corner_report.h"

#include <cmath>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/io/atomic_file.h"
#include "core/io/json_writer.h"
#include "core/mapping/ros_map.h"

namespace coopmap {

CornersResult runCorners(const CornersOptions& o) {
  const RosMap map = loadRosMap(o.map_yaml);
  CornersResult result = findCorners(map.classes, o.map_yaml, o);
  if (!o.out_dir.empty()) writeCorners(result, o.out_dir);
  return result;
}

CornersResult findCorners(const GridU8& classes, const std::string& source,
                          const CornersOptions& o) {
  const MapLimits& lim = classes.limits;
  CornerConfig config;
  config.arm_cells = std::max(2.0, o.arm_length / lim.resolution);
  const CornerDetector detector(classes, config);
  CornersResult result;
  result.search = detector.findAll();
  for (uint8_t e : detector.edges().cells) result.edge_cells += e;

  const int scale = o.scale > 0 ? o.scale : std::max(1, 1200 / std::max(lim.width, lim.height));
  cv::Mat img(lim.height * scale, lim.width * scale, CV_8UC3);
  for (int iy = 0; iy < lim.height; ++iy)
    for (int ix = 0; ix < lim.width; ++ix) {
      const auto c = static_cast<CellClass>(classes.at(ix, iy));
      cv::Vec3b colour = c == CellClass::kFree       ? cv::Vec3b(255, 255, 255)
                         : c == CellClass::kOccupied ? cv::Vec3b(60, 60, 60)
                         : c == CellClass::kUnknown  ? cv::Vec3b(170, 170, 170)
                                                     : cv::Vec3b(200, 215, 215);
      if (detector.edges().at(ix, iy)) colour = cv::Vec3b(230, 140, 0);  // edges: blue
      img(cv::Rect(ix * scale, (lim.height - 1 - iy) * scale, scale, scale)).setTo(colour);
    }
  auto pixel = [&](const Eigen::Vector2d& p) {
    return cv::Point(
        static_cast<int>(std::lround((p.x() - lim.origin.x()) / lim.resolution * scale)),
        static_cast<int>(
            std::lround((lim.height - (p.y() - lim.origin.y()) / lim.resolution) * scale)));
  };
  JsonWriter j;
  j.beginObject();
  j.value("map", source).value("resolution", lim.resolution);
  j.value("arm_length_m", o.arm_length).value("candidates", result.search.candidates);
  j.value("status", toString(result.search.status));
  j.beginArray("corners");
  for (const Corner& c : result.search.corners) {
    for (int arm = -1; arm <= 1; arm += 2) {
      const double a = c.heading + arm * M_PI / 4;
      const Eigen::Vector2d end =
          c.position + o.arm_length * Eigen::Vector2d(std::cos(a), std::sin(a));
      cv::line(img, pixel(c.position), pixel(end), cv::Scalar(0, 0, 230), 2, cv::LINE_AA);
    }
    cv::circle(img, pixel(c.position), 3 + scale, cv::Scalar(0, 0, 230), 1, cv::LINE_AA);
    j.beginObject();
    j.value("x", c.position.x()).value("y", c.position.y());
    j.value("heading_deg", c.heading * 180.0 / M_PI).value("rms_cells", c.rms);
    j.value("support", c.support).value("iterations", c.iterations);
    j.endObject();
  }
  j.endArray();
  j.endObject();
  std::vector<unsigned char> buf;
  if (!cv::imencode(".png", img, buf)) throw std::runtime_error("PNG encoding failed");
  result.png.assign(buf.begin(), buf.end());
  result.json = j.str();
  return result;
}

void writeCorners(const CornersResult& result, const std::string& out_dir) {
  std::filesystem::create_directories(out_dir);
  writeFileAtomic(out_dir + "/corners.png", result.png);
  writeFileAtomic(out_dir + "/corners.json", result.json);
}

}  // namespace coopmap
