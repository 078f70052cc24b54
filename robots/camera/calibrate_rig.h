// `coopmap calibrate`: the trinocular rig's calibration from checkerboard views, written in
// OpenCV FileStorage YAML for the camera driver (robots/camera/).
#pragma once

#include <string>

#include "core/calibration/rig_calibration.h"
#include "robots/camera/trinocular_camera.h"

namespace coopmap {

struct CalibrateOptions {
  CameraSources sources;  // reference, horizontal, vertical: image sequences or videos
  std::string board;      // "COLSxROWS" inner corners, e.g. "9x6"
  double square = 0.0;    // m, side of a square
  std::string out_file;   // calibration YAML
};

struct CalibrateResult {
  RigCalibration calibration;
  RigRectification rectification;
  int views = 0;                         // frames read from each camera
  std::array<int, kRigCameras> found{};  // views in which each camera found the board
  std::string report;                    // what the command prints
};

// Parses "COLSxROWS" (inner corners); throws std::invalid_argument naming --board.
Checkerboard parseBoard(const std::string& text, double square);

// Reads the three sequences, finds the board, calibrates, writes out_file. Throws
// std::runtime_error (the camera and source named) for unreadable or unequal sequences or too
// few views, std::invalid_argument for bad options.
CalibrateResult runCalibrate(const CalibrateOptions& options);

}  // namespace coopmap
