// Synthetic trinocular views of a textured box in front of a weakly textured background
// (both fronto-parallel, integer disparities) for the default L-rig: the horizontal
// partner sees a point of reference column x at x - d, the vertical one a point of
// reference row y at y + d. The box occludes the background in every view.
#pragma once

#include <cstdint>
#include <random>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace coopmap::test {

struct BoxScene {
  cv::Rect box{60, 30, 40, 60};  // the box in the reference image (px)
  int box_disparity = 8;         // px
  int background_disparity = 1;  // px
  int background_contrast = 6;   // grey levels of the background texture's spread
};

struct BoxViews {
  cv::Mat ref, hor, ver;
};

// 160 x 120 views of the scene.
inline BoxViews renderBoxScene(const BoxScene& s, uint32_t seed = 7) {
  const int w = 160, h = 120, m = 40;  // textures are indexed in reference coordinates + m
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> u(0, 255);
  cv::Mat fg(h + 2 * m, w + 2 * m, CV_8UC1), bg(h + 2 * m, w + 2 * m, CV_8UC1);
  for (cv::Mat* t : {&fg, &bg})
    for (int y = 0; y < t->rows; ++y)
      for (int x = 0; x < t->cols; ++x) t->at<uint8_t>(y, x) = static_cast<uint8_t>(u(rng));
  cv::GaussianBlur(fg, fg, cv::Size(0, 0), 1.0);
  cv::normalize(fg, fg, 0, 255, cv::NORM_MINMAX);
  cv::GaussianBlur(bg, bg, cv::Size(0, 0), 1.5);
  cv::normalize(bg, bg, 128 - s.background_contrast, 128 + s.background_contrast, cv::NORM_MINMAX);
  // What a view sees where the reference ray at (x, y) would meet the box: the box's own
  // point when it lies inside the box, else the background's point given by `back`.
  auto see = [&](int fx, int fy, int bx, int by) {
    return s.box.contains(cv::Point(fx, fy)) ? fg.at<uint8_t>(fy + m, fx + m)
                                             : bg.at<uint8_t>(by + m, bx + m);
  };
  const int df = s.box_disparity, db = s.background_disparity;
  BoxViews v{cv::Mat(h, w, CV_8UC1), cv::Mat(h, w, CV_8UC1), cv::Mat(h, w, CV_8UC1)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      v.ref.at<uint8_t>(y, x) = see(x, y, x, y);
      v.hor.at<uint8_t>(y, x) = see(x + df, y, x + db, y);
      v.ver.at<uint8_t>(y, x) = see(x, y - df, x, y - db);
    }
  return v;
}

}  // namespace coopmap::test
