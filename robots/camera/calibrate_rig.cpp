#include "robots/camera/calibrate_rig.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/calib3d.hpp>

namespace coopmap {

namespace {
std::string format(const char* fmt, double a = 0, double b = 0, double c = 0, double d = 0,
                   double e = 0, double f = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, fmt, a, b, c, d, e, f);
  return buf;
}
}  // namespace

Checkerboard parseBoard(const std::string& text, double square) {
  Checkerboard board;
  board.square = square;
  const size_t x = text.find_first_of("xX");
  auto bad = [&] {
    throw std::invalid_argument(
        "--board: expected COLSxROWS, the inner corners along a row and a column (e.g. 9x6), "
        "got '" +
        text + "'");
  };
  if (x == std::string::npos || x == 0 || x + 1 >= text.size()) bad();
  try {
    size_t used = 0;
    board.cols = std::stoi(text.substr(0, x), &used);
    if (used != x) bad();
    board.rows = std::stoi(text.substr(x + 1), &used);
    if (used != text.size() - x - 1) bad();
  } catch (const std::logic_error&) {
    bad();
  }
  if (!(square > 0.0))
    throw std::invalid_argument("--square: expected a positive side (m), got " +
                                std::to_string(square));
  board.validate();
  return board;
}

CalibrateResult runCalibrate(const CalibrateOptions& options) {
  const Checkerboard board = parseBoard(options.board, options.square);
  if (options.out_file.empty()) throw std::invalid_argument("--out: a file name is required");
  RawTrinocularCapture capture(options.sources);
  CalibrateResult result;
  std::vector<RigView> views;
  std::array<cv::Size, kRigCameras> sizes{};
  std::array<cv::Mat, kRigCameras> grey;
  while (capture.read(grey)) {
    RigView view;
    for (int c = 0; c < kRigCameras; ++c) {
      if (result.views == 0) sizes[c] = grey[c].size();
      if (grey[c].size() != sizes[c])
        throw std::runtime_error(std::string(rigCameraName(c)) + " camera ('" + options.sources[c] +
                                 "'): frame " + std::to_string(result.views) +
                                 " has another size than frame 0");
      if (auto corners = findCheckerboard(grey[c], board)) {
        view[c] = std::move(*corners);
        ++result.found[c];
      }
    }
    views.push_back(std::move(view));
    ++result.views;
  }
  if (result.views == 0) throw std::runtime_error("calibration: the sequences hold no frames");
  result.calibration = calibrateRig(views, sizes, board);
  result.rectification = rectifyRig(result.calibration);
  writeRigCalibration(options.out_file, result.calibration);

  const RigCalibration& cal = result.calibration;
  std::string& r = result.report;
  r += "board " + std::to_string(board.cols) + "x" + std::to_string(board.rows) +
       " inner corners, " + format("%.4g", board.square) + " m squares; " +
       std::to_string(result.views) + " views\n";
  r += "| camera | views with board | RMS px | fx | fy | cx | cy | k1 | k2 | p1 | p2 | k3 |\n"
       "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (int c = 0; c < kRigCameras; ++c) {
    const CameraCalibration& cam = cal.cameras[c];
    r += std::string("| ") + rigCameraName(c) + " | " + std::to_string(result.found[c]) + " | " +
         format("%.3f | %.2f | %.2f | %.2f | %.2f", cam.rms, cam.fx(), cam.fy(), cam.cx(),
                cam.cy()) +
         format(" | %.4f | %.4f | %.5f | %.5f | %.4f |\n", cam.distortion[0], cam.distortion[1],
                cam.distortion[2], cam.distortion[3], cam.distortion[4]);
  }
  r += "| partner | stereo views | stereo RMS px | position in reference frame (mm) | baseline "
       "mm | rotation deg |\n|---|---|---|---|---|---|\n";
  for (int c : {kHorizontalCamera, kVerticalCamera}) {
    const PartnerPose& p = cal.partner(c);
    const Eigen::Vector3d b = p.position() * 1000.0;
    cv::Vec3d rvec;
    cv::Rodrigues(p.R, rvec);
    r += std::string("| ") + rigCameraName(c) + " | " + std::to_string(p.views) + " | " +
         format("%.3f | (%.2f, %.2f, %.2f) | %.2f | %.3f |\n", p.rms, b.x(), b.y(), b.z(), b.norm(),
                cv::norm(rvec) * 180.0 / M_PI);
  }
  const RigRectification& rect = result.rectification;
  const CameraIntrinsics& k = rect.rig.intrinsics;
  r += format("rectified: %.0fx%.0f px, fx %.2f, fy %.2f, cx %.2f, cy %.2f; ", k.width, k.height,
              k.fx, k.fy, k.cx, k.cy) +
       format(
           "horizontal offset %.2f mm, vertical offset %.2f mm, baselines off perpendicular "
           "by %.3f deg\n",
           rect.rig.horizontal_offset.x() * 1000.0, rect.rig.vertical_offset.y() * 1000.0,
           rect.orthogonality_error * 180.0 / M_PI);
  r += options.out_file + " written\n";
  return result;
}

}  // namespace coopmap
