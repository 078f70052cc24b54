#include "core/mapping/map_io.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/io/atomic_file.h"

namespace coopmap {

void writeRosMap(const OccupancyGrid& grid, const std::string& dir, const std::string& name) {
  const MapLimits& lim = grid.limits();
  std::string pgm =
      "P5\n" + std::to_string(lim.width) + " " + std::to_string(lim.height) + "\n255\n";
  const size_t header = pgm.size();
  pgm.resize(header + lim.size());
  for (int row = 0; row < lim.height; ++row) {
    const int iy = lim.height - 1 - row;  // north up
    for (int ix = 0; ix < lim.width; ++ix) {
      unsigned char v = 205;  // unknown, as map_saver writes it
      if (grid.seen(ix, iy)) {
        const double p = grid.probability(ix, iy);
        v = static_cast<unsigned char>(std::lround(255.0 * (1.0 - p)));
      }
      pgm[header + static_cast<size_t>(row) * lim.width + ix] = static_cast<char>(v);
    }
  }
  writeFileAtomic(dir + "/" + name + ".pgm", pgm);

  const double p_occ = 1.0 / (1.0 + std::exp(-grid.config().occupied_threshold / 100.0));
  const double p_free = 1.0 / (1.0 + std::exp(-grid.config().free_threshold / 100.0));
  char yaml[512];
  std::snprintf(yaml, sizeof yaml,
                "image: %s.pgm\nresolution: %.6f\norigin: [%.6f, %.6f, 0.0]\nnegate: 0\n"
                "occupied_thresh: %.4f\nfree_thresh: %.4f\n",
                name.c_str(), lim.resolution, lim.origin.x(), lim.origin.y(), p_occ, p_free);
  writeFileAtomic(dir + "/" + name + ".yaml", yaml);
}

std::string encodeMapPng(const OccupancyGrid& grid, const std::vector<TrajectoryOverlay>& overlays,
                         int scale) {
  const MapLimits& lim = grid.limits();
  cv::Mat img(lim.height * scale, lim.width * scale, CV_8UC3);
  for (int iy = 0; iy < lim.height; ++iy) {
    for (int ix = 0; ix < lim.width; ++ix) {
      cv::Vec3b c(150, 150, 150);
      if (grid.seen(ix, iy)) {
        switch (grid.state(ix, iy)) {
          case CellState::kFree:
            c = cv::Vec3b(255, 255, 255);
            break;
          case CellState::kOccupied:
            c = cv::Vec3b(0, 0, 0);
            break;
          default:
            c = cv::Vec3b(200, 215, 215);
            break;  // seen, undecided
        }
      }
      const int row = (lim.height - 1 - iy) * scale;
      img(cv::Rect(ix * scale, row, scale, scale)).setTo(c);
    }
  }
  auto toPixel = [&](const Pose2& p) {
    return cv::Point2d((p.x - lim.origin.x()) / lim.resolution * scale,
                       (lim.height - (p.y - lim.origin.y()) / lim.resolution) * scale);
  };
  for (const TrajectoryOverlay& o : overlays) {
    const cv::Scalar colour(o.b, o.g, o.r);
    for (size_t i = 1; i < o.poses.size(); ++i)
      cv::line(img, toPixel(o.poses[i - 1].pose), toPixel(o.poses[i].pose), colour, 1, cv::LINE_AA);
    if (!o.poses.empty()) cv::circle(img, toPixel(o.poses.front().pose), 2 * scale, colour, 1);
  }
  std::vector<unsigned char> buf;
  if (!cv::imencode(".png", img, buf)) throw std::runtime_error("PNG encoding failed");
  return std::string(buf.begin(), buf.end());
}

std::string encodeEvaluationPng(const OccupancyGrid& grid, const GridU8& truth, int scale,
                                const GridU8* drivable) {
  const MapLimits& lim = grid.limits();
  cv::Mat img(lim.height * scale, lim.width * scale, CV_8UC3);
  auto near = [&](int x, int y, auto&& pred) {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (lim.contains(x + dx, y + dy) && pred(x + dx, y + dy)) return true;
    return false;
  };
  for (int iy = 0; iy < lim.height; ++iy) {
    for (int ix = 0; ix < lim.width; ++ix) {
      const bool occ = grid.state(ix, iy) == CellState::kOccupied;
      cv::Vec3b c = grid.seen(ix, iy) ? cv::Vec3b(255, 255, 255) : cv::Vec3b(170, 170, 170);
      if (truth.at(ix, iy)) {
        const bool wall =
            near(ix, iy, [&](int a, int b) { return !truth.at(a, b) && grid.seen(a, b); });
        const bool found =
            near(ix, iy, [&](int a, int b) { return grid.state(a, b) == CellState::kOccupied; });
        c = !wall ? cv::Vec3b(90, 90, 90) : found ? cv::Vec3b(0, 0, 0) : cv::Vec3b(0, 0, 230);
      } else if (drivable && !drivable->at(ix, iy)) {
        c = grid.seen(ix, iy) ? cv::Vec3b(215, 200, 200) : cv::Vec3b(150, 140, 140);
      } else if (occ) {
        const bool by_wall = near(ix, iy, [&](int a, int b) { return truth.at(a, b) != 0; });
        c = by_wall ? cv::Vec3b(120, 120, 120) : cv::Vec3b(230, 80, 0);
      }
      img(cv::Rect(ix * scale, (lim.height - 1 - iy) * scale, scale, scale)).setTo(c);
    }
  }
  std::vector<unsigned char> buf;
  if (!cv::imencode(".png", img, buf)) throw std::runtime_error("PNG encoding failed");
  return std::string(buf.begin(), buf.end());
}

void writeMapPng(const std::string& path, const OccupancyGrid& grid,
                 const std::vector<TrajectoryOverlay>& overlays, int scale) {
  writeFileAtomic(path, encodeMapPng(grid, overlays, scale));
}

}  // namespace coopmap
