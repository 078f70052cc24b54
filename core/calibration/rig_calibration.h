// Calibration of the trinocular L-rig from checkerboard views (OpenCV's pinhole model with
// k1 k2 p1 p2 k3 distortion), and rectification of its three cameras to the geometry the
// trinocular matcher expects: one common intrinsic matrix and orientation, the horizontal
// partner displaced along image rows, the vertical partner along image columns.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>
#include <opencv2/core/matx.hpp>
#include <opencv2/core/types.hpp>

#include "core/geometry/camera.h"

namespace coopmap {

// The three cameras of the rig, in the order used by every array below.
enum RigCamera : int { kReferenceCamera = 0, kHorizontalCamera = 1, kVerticalCamera = 2 };
inline constexpr int kRigCameras = 3;
// "reference", "horizontal", "vertical".
const char* rigCameraName(int camera);

// A planar checkerboard target: inner corners counted along a row (cols) and a column (rows).
// Boards with one even and one odd count have no 180-degree ambiguity.
struct Checkerboard {
  int cols = 9;
  int rows = 6;
  double square = 0.04;  // m, side of one square

  // Corner positions in the board frame (m, z = 0), row by row, as the detector orders them.
  std::vector<cv::Point3f> objectPoints() const;
  // Throws std::invalid_argument naming the field and the bad value.
  void validate() const;
};

// Finds the board's inner corners in a grey (or colour) image to sub-pixel accuracy; nullopt
// when the whole board is not visible. Corners are ordered row by row from the board's
// first corner, the one nearest the image's top-left for an upright board.
std::optional<std::vector<cv::Point2f>> findCheckerboard(const cv::Mat& image,
                                                         const Checkerboard& board);

// One camera: OpenCV's pinhole model with distortion coefficients (k1, k2, p1, p2, k3).
struct CameraCalibration {
  int width = 0, height = 0;                       // px, image size
  cv::Matx33d camera_matrix = cv::Matx33d::eye();  // fx 0 cx; 0 fy cy; 0 0 1 (px)
  cv::Vec<double, 5> distortion{0, 0, 0, 0, 0};    // k1, k2, p1, p2, k3
  double rms = 0.0;                                // px, reprojection RMS of its calibration
  int views = 0;                                   // views it was estimated from

  double fx() const { return camera_matrix(0, 0); }
  double fy() const { return camera_matrix(1, 1); }
  double cx() const { return camera_matrix(0, 2); }
  double cy() const { return camera_matrix(1, 2); }
};

// A partner camera relative to the reference camera, as cv::stereoCalibrate gives it: a point
// x in the reference camera frame is R x + T in the partner's frame (m).
struct PartnerPose {
  cv::Matx33d R = cv::Matx33d::eye();
  cv::Vec3d T{0, 0, 0};
  double rms = 0.0;  // px, reprojection RMS of the stereo calibration
  int views = 0;

  // The partner's optical centre in the reference camera frame (m): -R^T T.
  Eigen::Vector3d position() const;
};

// The whole rig: three cameras, the partners' poses, and the board it was calibrated with.
struct RigCalibration {
  std::array<CameraCalibration, kRigCameras> cameras;
  PartnerPose horizontal, vertical;
  Checkerboard board;

  const PartnerPose& partner(int camera) const {
    return camera == kHorizontalCamera ? horizontal : vertical;
  }
  // Throws std::invalid_argument naming the field when a value is impossible (non-positive
  // focal length or size, a rotation that is not one, a zero baseline).
  void validate() const;
};

// Corners found in one view by each camera (empty where the board was not found).
using RigView = std::array<std::vector<cv::Point2f>, kRigCameras>;

// Calibrates each camera from the views where it saw the board (cv::calibrateCamera), then
// each partner against the reference from the views both saw (cv::stereoCalibrate with the
// intrinsics fixed). `sizes` are the cameras' image sizes. Throws std::runtime_error naming
// the camera when it has fewer than 3 views (or a pair fewer than 3 common views).
RigCalibration calibrateRig(const std::vector<RigView>& views,
                            const std::array<cv::Size, kRigCameras>& sizes,
                            const Checkerboard& board);

// How the rectified images are laid out.
struct RectificationOptions {
  int width = 0, height = 0;  // px; 0: the reference camera's image size
  double focal = 0.0;         // px; 0: the mean of the three cameras' fx and fy
  // Scales the rectified fy so that one disparity step moves the vertical partner's image by
  // exactly as many pixels as the horizontal partner's (the matcher's fast unit-step path
  // when the two baselines differ slightly); pixels are then very slightly non-square.
  bool equal_disparity_steps = true;
};

// The rectified rig and, per camera, the rotation from its frame into the common rectified
// frame (the R of cv::initUndistortRectifyMap).
struct RigRectification {
  // Common intrinsics, partners displaced along x and y only (mount_position left default).
  TrinocularRig rig;
  cv::Matx33d camera_matrix = cv::Matx33d::eye();
  std::array<cv::Matx33d, kRigCameras> rotations;
  // The partners' optical centres in the rectified frame as calibrated (m). The plane of the
  // three centres is the rectified image plane, so z is 0; a residual y of the horizontal and
  // x of the vertical partner (equal in size) remain when the baselines are not orthogonal.
  Eigen::Vector3d horizontal_exact{0, 0, 0}, vertical_exact{0, 0, 0};
  // Angle (rad) by which the two baselines miss being perpendicular.
  double orthogonality_error = 0.0;
};

// Rectifies the rig to the L geometry: x along the horizontal baseline and y along the
// vertical baseline (the two made orthogonal symmetrically), z perpendicular to both, facing
// the way the reference camera looks. Throws std::invalid_argument for bad options or a rig
// whose baselines are (nearly) parallel.
RigRectification rectifyRig(const RigCalibration& calibration,
                            const RectificationOptions& options = {});

// cv::remap maps (CV_32FC1 x and y) that undistort and rectify one camera's images.
struct RectificationMap {
  cv::Mat x, y;
};
RectificationMap rectificationMap(const RigCalibration& calibration,
                                  const RigRectification& rectification, int camera);

// Writes the calibration (and, for other tools, its rectification) in OpenCV FileStorage YAML.
// Throws std::runtime_error naming the file when it cannot be written.
void writeRigCalibration(const std::string& path, const RigCalibration& calibration,
                         const RectificationOptions& options = {});
// Reads a file written by writeRigCalibration; the rectification is recomputed, not read.
// Throws ConfigError naming the file, and the field, when it is missing or malformed.
RigCalibration readRigCalibration(const std::string& path);

}  // namespace coopmap
