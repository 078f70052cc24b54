// Lens distortion for simulated cameras: turns ideal pinhole renders into the images of a
// camera with OpenCV's distortion model, exactly as cv::projectPoints would place each ray.
//
// Convention (OpenCV's, coefficients k1 k2 p1 p2 k3): a ray with normalized coordinates
// (x, y) = (X/Z, Y/Z) in the camera frame (x right, y down, z forward), r^2 = x^2 + y^2, is
// seen at pixel
//   u = fx * (x * (1 + k1 r^2 + k2 r^4 + k3 r^6) + 2 p1 x y + p2 (r^2 + 2 x^2)) + cx
//   v = fy * (y * (1 + k1 r^2 + k2 r^4 + k3 r^6) + p1 (r^2 + 2 y^2) + 2 p2 x y) + cy.
// So a camera calibrated with cv::calibrateCamera on these images recovers (fx, fy, cx, cy)
// and the coefficients themselves.
#pragma once

#include <utility>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "core/geometry/camera.h"

namespace coopmap::sim {

struct LensDistortion {
  double k1 = 0.0, k2 = 0.0;  // radial
  double p1 = 0.0, p2 = 0.0;  // tangential
  double k3 = 0.0;            // radial, sixth order

  bool enabled() const { return k1 != 0 || k2 != 0 || p1 != 0 || p2 != 0 || k3 != 0; }
  // Throws std::invalid_argument naming the field when a coefficient is out of the range
  // where the model stays invertible over a camera's image (|k1| <= 1, |k2|, |k3| <= 2,
  // |p1|, |p2| <= 0.1).
  void validate() const;
};

// One distorted camera: each of its pixels is traced back (cv::undistortPoints, iterated
// to 1e-10) to its ray, which is looked up in a supersampled pinhole render of the scene.
// The render is box-filtered over one output pixel's footprint (supersample x supersample
// render pixels, which antialiases edges) and interpolated bilinearly.
class LensDistorter {
 public:
  // `camera`: the distorted camera's intrinsics and image size. `render`: the pinhole
  // intrinsics of the renders given to apply() (see renderIntrinsicsFor); `supersample`: the
  // render's scale over the camera (odd, 1..7).
  LensDistorter(const CameraIntrinsics& camera, const LensDistortion& distortion,
                const CameraIntrinsics& render, int supersample);

  // Pinhole intrinsics for rendering the views of all `cameras` at `supersample` times the
  // largest focal length among them, wide enough for every pixel of every camera (plus a
  // margin for the filters); the principal point need not be centred. Throws
  // std::invalid_argument when supersample is not odd in 1..7 or the render would exceed
  // 4096 px a side.
  static CameraIntrinsics renderIntrinsicsFor(
      const std::vector<std::pair<CameraIntrinsics, LensDistortion>>& cameras, int supersample);

  // The distorted camera's image (CV_8UC1, camera size) of an ideal render (CV_8UC1, the
  // render intrinsics' size).
  void apply(const cv::Mat& render, cv::Mat& image) const;

  // Where the ray of camera pixel (u, v) lands in the render (px), as apply() samples it.
  cv::Point2f renderPixel(int u, int v) const {
    return {map_x_.at<float>(v, u), map_y_.at<float>(v, u)};
  }

 private:
  CameraIntrinsics camera_, render_;
  int supersample_ = 1;
  cv::Mat map_x_, map_y_;  // CV_32FC1, camera size: render coordinates per camera pixel
};

}  // namespace coopmap::sim
