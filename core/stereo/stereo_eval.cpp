#include "core/stereo/stereo_eval.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace coopmap {

DisparityScore scoreDisparity(const cv::Mat& disparity, const cv::Mat& truth, double bad_threshold,
                              int border) {
  if (disparity.type() != CV_32F || truth.type() != CV_32F || disparity.size() != truth.size())
    throw std::invalid_argument("scoreDisparity: expected two CV_32F images of one size");
  DisparityScore s;
  double abs_sum = 0.0, signed_sum = 0.0, relative_sum = 0.0;
  for (int v = border; v < disparity.rows - border; ++v)
    for (int u = border; u < disparity.cols - border; ++u) {
      const float t = truth.at<float>(v, u);
      if (!(t > 0.0f)) continue;
      ++s.evaluated;
      const float d = disparity.at<float>(v, u);
      if (!(d > 0.0f)) continue;
      ++s.valid;
      const double e = std::abs(double(d) - t);
      abs_sum += e;
      if (e > bad_threshold) {
        ++s.bad;
      } else {
        ++s.good;
        signed_sum += double(d) - t;
        relative_sum += double(t) / d - 1.0;
      }
    }
  s.density = s.evaluated ? double(s.valid) / s.evaluated : 0.0;
  s.bad_pixel_rate = s.valid ? double(s.bad) / s.valid : 0.0;
  s.mae = s.valid ? abs_sum / s.valid : 0.0;
  s.bias = s.good ? signed_sum / s.good : 0.0;
  s.depth_scale_error = s.good ? relative_sum / s.good : 0.0;
  return s;
}

cv::Mat disparityFromDepth(const cv::Mat& depth, double focal_baseline) {
  cv::Mat out(depth.size(), CV_32F);
  for (int v = 0; v < depth.rows; ++v)
    for (int u = 0; u < depth.cols; ++u) {
      const float z = depth.at<float>(v, u);
      out.at<float>(v, u) = z > 0.0f ? static_cast<float>(focal_baseline / z) : 0.0f;
    }
  return out;
}

cv::Mat colourDisparity(const cv::Mat& disparity, double max_disparity) {
  cv::Mat grey(disparity.size(), CV_8UC1);
  for (int v = 0; v < disparity.rows; ++v)
    for (int u = 0; u < disparity.cols; ++u) {
      const float d = disparity.at<float>(v, u);
      grey.at<uint8_t>(v, u) =
          d > 0.0f ? static_cast<uint8_t>(std::clamp(255.0 * d / max_disparity, 0.0, 255.0)) : 0;
    }
  cv::Mat colour;
  cv::applyColorMap(grey, colour, cv::COLORMAP_JET);
  for (int v = 0; v < disparity.rows; ++v)
    for (int u = 0; u < disparity.cols; ++u)
      if (!(disparity.at<float>(v, u) > 0.0f)) colour.at<cv::Vec3b>(v, u) = cv::Vec3b(0, 0, 0);
  return colour;
}

cv::Mat errorPicture(const cv::Mat& disparity, const cv::Mat& truth, double bad_threshold) {
  double max_truth = 1.0;
  cv::minMaxLoc(truth, nullptr, &max_truth);
  cv::Mat out(disparity.size(), CV_8UC3);
  for (int v = 0; v < disparity.rows; ++v)
    for (int u = 0; u < disparity.cols; ++u) {
      const float t = truth.at<float>(v, u), d = disparity.at<float>(v, u);
      cv::Vec3b c(0, 0, 0);
      if (!(t > 0.0f)) {
        c = cv::Vec3b(90, 30, 0);
      } else if (d > 0.0f) {
        const auto g = static_cast<uint8_t>(80 + 175 * std::clamp(t / max_truth, 0.0, 1.0));
        c = std::abs(d - t) > bad_threshold ? cv::Vec3b(0, 0, 255) : cv::Vec3b(g, g, g);
      }
      out.at<cv::Vec3b>(v, u) = c;
    }
  return out;
}

}  // namespace coopmap
