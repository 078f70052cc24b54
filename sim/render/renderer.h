// Headless OpenGL renderer (OSMesa, no X server, no GPU) of a world's textured solids:
// grey camera images and ground-truth depth from any camera pose.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>

#include "core/geometry/camera.h"
#include "sim/world/world.h"

namespace coopmap::sim {

// A vertical cylinder to draw (robots and people move, so they are passed per frame).
struct DynamicCylinder {
  Eigen::Vector2d center{0.0, 0.0};
  double radius = 0.2;
  double height = 1.0;
};

class Renderer {
 public:
  // Builds the static scene (textures uploaded once). Throws std::runtime_error when no
  // OSMesa context can be created.
  Renderer(const World& world, const CameraIntrinsics& intrinsics, double near_m = 0.05,
           double far_m = 60.0);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Renders the view of a camera at X_WC (OpenCV camera frame: x right, y down, z forward,
  // in the 3D world frame: z up). `grey` gets CV_8UC1; `depth`, if given, CV_32F metres
  // along the optical axis (0 where nothing was hit). `others` (robots, people) are drawn
  // as cylinders, `boxes` (doors now closed) with their textures.
  void render(const Eigen::Isometry3d& X_WC, const std::vector<DynamicCylinder>& others,
              const std::vector<SolidBox>& boxes, cv::Mat& grey, cv::Mat* depth = nullptr);
  // Renders up to kMaxViews cameras in one pass: side by side in one framebuffer, one
  // flush and one read-back of the grey channel (and of the first view's depth, if asked).
  // Images are the same as rendering each view alone.
  static constexpr int kMaxViews = 3;
  void renderViews(const std::vector<Eigen::Isometry3d>& X_WCs,
                   const std::vector<DynamicCylinder>& others, const std::vector<SolidBox>& boxes,
                   const std::vector<cv::Mat*>& greys, cv::Mat* first_depth = nullptr);

  const CameraIntrinsics& intrinsics() const { return intrinsics_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  CameraIntrinsics intrinsics_;
};

}  // namespace coopmap::sim
