// Pinhole cameras and the trinocular L-rig (reference, horizontal partner, vertical partner).
#pragma once

#include <array>
#include <cmath>

#include <Eigen/Core>

namespace coopmap {

// Pinhole intrinsics in pixels; pixel centres at integer coordinates (OpenCV convention).
struct CameraIntrinsics {
  int width = 160;
  int height = 120;
  double fx = 80.0;
  double fy = 80.0;
  double cx = 79.5;
  double cy = 59.5;

  // Square-pixel intrinsics with a given horizontal field of view (radians), centred.
  static CameraIntrinsics fromFov(int width, int height, double hfov_rad) {
    CameraIntrinsics k;
    k.width = width;
    k.height = height;
    k.fx = k.fy = 0.5 * width / std::tan(0.5 * hfov_rad);
    k.cx = 0.5 * (width - 1);
    k.cy = 0.5 * (height - 1);
    return k;
  }
};

// A rectified trinocular rig. Camera frames follow OpenCV (x right, y down, z forward);
// all three cameras share intrinsics and orientation. Partners are offset from the
// reference camera in its own frame, in metres (any sign, any length).
struct TrinocularRig {
  CameraIntrinsics intrinsics;
  Eigen::Vector3d horizontal_offset{0.10, 0.0, 0.0};  // partner along +x (to the right)
  Eigen::Vector3d vertical_offset{0.0, -0.10, 0.0};   // partner along -y (above)
  // Reference camera in the robot frame (REP-103): position (m), looking along +x.
  Eigen::Vector3d mount_position{0.10, 0.0, 0.90};

  // Baseline (m) that defines one unit of disparity: the horizontal partner's distance.
  double referenceBaseline() const { return horizontal_offset.norm(); }
};

}  // namespace coopmap
