// The camera driver of a real trinocular rig: three cv::VideoCapture sources (V4L2 devices,
// or video files and image sequences for tests and recorded data) grabbed together, turned
// grey, undistorted and rectified to the L-rig geometry the trinocular matcher expects.
#pragma once

#include <array>
#include <optional>
#include <string>

#include <opencv2/core/mat.hpp>
#include <opencv2/videoio.hpp>

#include "core/calibration/rig_calibration.h"
#include "core/robot/robot_interface.h"

namespace coopmap {

// Sources of the reference, horizontal and vertical cameras, each one of: a V4L2 device
// index ("0") or path ("/dev/video0"); an image sequence as a printf pattern
// ("images/left_%04d.png", numbered from 0 or 1 up); a video file.
using CameraSources = std::array<std::string, kRigCameras>;

// Three raw cameras grabbed in sync: grab() on all three first, then retrieve(), so the
// exposures are as close together as the devices allow. Not copyable (owns the devices).
class RawTrinocularCapture {
 public:
  // Opens the three sources. Throws std::runtime_error naming the camera and the source
  // when one cannot be opened.
  explicit RawTrinocularCapture(const CameraSources& sources);
  RawTrinocularCapture(const RawTrinocularCapture&) = delete;
  RawTrinocularCapture& operator=(const RawTrinocularCapture&) = delete;

  // Reads the next frame of each camera as grey CV_8UC1 images. Returns false when all three
  // sources have ended; throws std::runtime_error naming the camera, the source and the frame
  // when only some of them have a frame, or a frame cannot be decoded.
  bool read(std::array<cv::Mat, kRigCameras>& grey);
  // Frames read so far (the index of the next frame).
  int frames() const { return frames_; }
  const CameraSources& sources() const { return sources_; }

 private:
  CameraSources sources_;
  std::array<cv::VideoCapture, kRigCameras> captures_;
  int frames_ = 0;
};

// Reads a whole source (image sequence or video file) as grey images; throws as above.
std::vector<cv::Mat> readGreySequence(const std::string& source, const std::string& camera_name);

// The rig's cameras, rectified: each capture is three rectified 8-bit images of the rig()
// geometry (common intrinsics; partners along x and y). Not copyable.
class TrinocularCamera {
 public:
  // Opens the sources (throws as RawTrinocularCapture) and builds the rectification maps of
  // `calibration` (throws std::invalid_argument for a calibration that cannot be rectified).
  TrinocularCamera(const CameraSources& sources, const RigCalibration& calibration,
                   const RectificationOptions& options = {});
  // Sources that give rectified images of `rig` already (a camera head that rectifies itself,
  // as the Triclops does; a recording's images): the frames are those images, grey.
  TrinocularCamera(const CameraSources& sources, const TrinocularRig& rig);
  TrinocularCamera(const TrinocularCamera&) = delete;
  TrinocularCamera& operator=(const TrinocularCamera&) = delete;

  // The rectified rig the frames follow (mount_position: TrinocularRig's default; the robot
  // description sets it).
  const TrinocularRig& rig() const { return rectification_.rig; }
  const RigRectification& rectification() const { return rectification_; }

  // Captures the next frame, stamped `stamp` (s, robot clock; odometry left for the robot
  // driver to fill in). nullopt when all sources have ended; throws std::runtime_error
  // naming the camera and source when a frame is missing or has the wrong size.
  std::optional<TrinocularFrame> capture(double stamp = 0.0);

  // Rectifies three raw images (grey or colour, each its camera's calibrated size) into
  // `frame`'s images. Throws std::runtime_error naming the camera on a size mismatch.
  void rectify(const std::array<cv::Mat, kRigCameras>& raw, TrinocularFrame& frame) const;

 private:
  RawTrinocularCapture capture_;
  bool rectified_sources_ = false;
  RigCalibration calibration_;
  RigRectification rectification_;
  std::array<RectificationMap, kRigCameras> maps_;
};

}  // namespace coopmap
