#include "sim/sensors/lens_distortion.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace coopmap::sim {

namespace {
cv::Matx33d cameraMatrix(const CameraIntrinsics& k) {
  return {k.fx, 0.0, k.cx, 0.0, k.fy, k.cy, 0.0, 0.0, 1.0};
}

cv::Vec<double, 5> coefficients(const LensDistortion& d) { return {d.k1, d.k2, d.p1, d.p2, d.k3}; }

// Traces pixels of a distorted camera back to their rays, projected by `P` (identity:
// normalized coordinates). Iterated until the rays reproject within 1e-10 px.
std::vector<cv::Point2d> undistort(const std::vector<cv::Point2d>& pixels,
                                   const CameraIntrinsics& k, const LensDistortion& d,
                                   const cv::Matx33d& P) {
  std::vector<cv::Point2d> out;
  cv::undistortPoints(
      pixels, out, cameraMatrix(k), coefficients(d), cv::noArray(), P,
      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 500, 1e-10));
  return out;
}

void checkSupersample(int supersample) {
  if (supersample < 1 || supersample > 7 || supersample % 2 == 0)
    throw std::invalid_argument(
        "lens distortion: supersample: expected an odd number in 1..7, got " +
        std::to_string(supersample));
}
}  // namespace

void LensDistortion::validate() const {
  auto check = [](const char* field, double v, double limit) {
    if (!(std::abs(v) <= limit))
      throw std::invalid_argument(std::string("lens distortion: field '") + field +
                                  "': expected a coefficient in [-" + std::to_string(limit) + ", " +
                                  std::to_string(limit) + "], got " + std::to_string(v));
  };
  check("k1", k1, 1.0);
  check("k2", k2, 2.0);
  check("p1", p1, 0.1);
  check("p2", p2, 0.1);
  check("k3", k3, 2.0);
}

CameraIntrinsics LensDistorter::renderIntrinsicsFor(
    const std::vector<std::pair<CameraIntrinsics, LensDistortion>>& cameras, int supersample) {
  checkSupersample(supersample);
  if (cameras.empty()) throw std::invalid_argument("lens distortion: no cameras given");
  double focal = 0.0;
  double lo_x = std::numeric_limits<double>::infinity(), lo_y = lo_x, hi_x = -lo_x, hi_y = -lo_x;
  for (const auto& [k, d] : cameras) {
    d.validate();
    focal = std::max({focal, k.fx, k.fy});
    // The image's outline, half a pixel outside the outermost pixel centres.
    std::vector<cv::Point2d> outline;
    const double l = -0.5, t = -0.5, r = k.width - 0.5, b = k.height - 0.5;
    for (int i = 0; i <= 64; ++i) {
      const double s = i / 64.0;
      outline.insert(
          outline.end(),
          {{l + s * (r - l), t}, {l + s * (r - l), b}, {l, t + s * (b - t)}, {r, t + s * (b - t)}});
    }
    for (const cv::Point2d& p : undistort(outline, k, d, cv::Matx33d::eye())) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y))
        throw std::invalid_argument(
            "lens distortion: the model cannot be inverted at the image border");
      lo_x = std::min(lo_x, p.x), hi_x = std::max(hi_x, p.x);
      lo_y = std::min(lo_y, p.y), hi_y = std::max(hi_y, p.y);
    }
  }
  CameraIntrinsics render;
  render.fx = render.fy = supersample * focal;
  const double margin = 2.0 * supersample + 2.0;  // px of the render: box filter and bilinear taps
  render.cx = -render.fx * lo_x + margin;
  render.cy = -render.fy * lo_y + margin;
  render.width = static_cast<int>(std::ceil(render.fx * (hi_x - lo_x) + 2.0 * margin)) + 1;
  render.height = static_cast<int>(std::ceil(render.fy * (hi_y - lo_y) + 2.0 * margin)) + 1;
  if (render.width > 4096 || render.height > 4096)
    throw std::invalid_argument("lens distortion: the render would be " +
                                std::to_string(render.width) + "x" + std::to_string(render.height) +
                                " px; at most 4096 a side (lower supersample)");
  return render;
}

LensDistorter::LensDistorter(const CameraIntrinsics& camera, const LensDistortion& distortion,
                             const CameraIntrinsics& render, int supersample)
    : camera_(camera), render_(render), supersample_(supersample) {
  checkSupersample(supersample);
  distortion.validate();
  std::vector<cv::Point2d> pixels;
  pixels.reserve(static_cast<size_t>(camera.width) * camera.height);
  for (int v = 0; v < camera.height; ++v)
    for (int u = 0; u < camera.width; ++u) pixels.emplace_back(u, v);
  const std::vector<cv::Point2d> at = undistort(pixels, camera, distortion, cameraMatrix(render));
  map_x_.create(camera.height, camera.width, CV_32FC1);
  map_y_.create(camera.height, camera.width, CV_32FC1);
  size_t i = 0;
  for (int v = 0; v < camera.height; ++v)
    for (int u = 0; u < camera.width; ++u, ++i) {
      map_x_.at<float>(v, u) = static_cast<float>(at[i].x);
      map_y_.at<float>(v, u) = static_cast<float>(at[i].y);
    }
}

void LensDistorter::apply(const cv::Mat& render, cv::Mat& image) const {
  if (render.type() != CV_8UC1 || render.cols != render_.width || render.rows != render_.height)
    throw std::invalid_argument("lens distortion: expected a CV_8UC1 render of " +
                                std::to_string(render_.width) + "x" +
                                std::to_string(render_.height) + " px");
  cv::Mat work;
  render.convertTo(work, CV_32F);
  if (supersample_ > 1)
    cv::blur(work, work, cv::Size(supersample_, supersample_), cv::Point(-1, -1),
             cv::BORDER_REPLICATE);
  cv::Mat out;
  cv::remap(work, out, map_x_, map_y_, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  out.convertTo(image, CV_8U);  // rounds and saturates
}

}  // namespace coopmap::sim
