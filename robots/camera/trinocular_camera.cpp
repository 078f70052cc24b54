#include "robots/camera/trinocular_camera.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace coopmap {

namespace {
bool isDeviceIndex(const std::string& s) {
  if (s.empty() || s.size() > 3) return false;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

// The file a printf pattern names for frame `index`.
std::string patternFile(const std::string& pattern, int index) {
  std::vector<char> buf(pattern.size() + 32);
  std::snprintf(buf.data(), buf.size(), pattern.c_str(), index);
  return buf.data();
}

// Opens one source, or throws naming the camera and what was tried.
void openSource(cv::VideoCapture& cap, const std::string& source, const std::string& camera) {
  const std::string what = camera + " camera: cannot open '" + source + "'";
  if (source.empty()) throw std::runtime_error(camera + " camera: no source given");
  if (isDeviceIndex(source)) {
    if (!cap.open(std::stoi(source), cv::CAP_V4L2))
      throw std::runtime_error(what + " (V4L2 device /dev/video" + source + ")");
    return;
  }
  if (source.rfind("/dev/", 0) == 0) {
    if (!cap.open(source, cv::CAP_V4L2)) throw std::runtime_error(what + " (V4L2 device)");
    return;
  }
  if (source.find('%') != std::string::npos) {
    const std::string first = patternFile(source, 0), second = patternFile(source, 1);
    if (!std::filesystem::exists(first) && !std::filesystem::exists(second))
      throw std::runtime_error(what + ": no image sequence (neither " + first + " nor " + second +
                               " exists)");
    if (!cap.open(source, cv::CAP_IMAGES)) throw std::runtime_error(what + " as an image sequence");
    return;
  }
  if (!std::filesystem::exists(source)) throw std::runtime_error(what + ": no such file");
  if (!cap.open(source)) throw std::runtime_error(what + " as a video file");
}

void toGrey(const cv::Mat& in, cv::Mat& out) {
  if (in.channels() == 1)
    in.copyTo(out);
  else
    cv::cvtColor(in, out, in.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  if (out.depth() != CV_8U) out.convertTo(out, CV_8U);
}

std::string frameName(const std::string& source, int frame) {
  if (source.find('%') != std::string::npos)
    return "frame " + std::to_string(frame) + " (around " + patternFile(source, frame) + ")";
  return "frame " + std::to_string(frame);
}
}  // namespace

RawTrinocularCapture::RawTrinocularCapture(const CameraSources& sources) : sources_(sources) {
  for (int c = 0; c < kRigCameras; ++c) openSource(captures_[c], sources_[c], rigCameraName(c));
}

bool RawTrinocularCapture::read(std::array<cv::Mat, kRigCameras>& grey) {
  std::array<bool, kRigCameras> grabbed{};
  for (int c = 0; c < kRigCameras; ++c) grabbed[c] = captures_[c].grab();
  if (!grabbed[0] && !grabbed[1] && !grabbed[2]) return false;
  for (int c = 0; c < kRigCameras; ++c)
    if (!grabbed[c])
      throw std::runtime_error(std::string(rigCameraName(c)) + " camera ('" + sources_[c] +
                               "'): " + frameName(sources_[c], frames_) +
                               " is missing while the other cameras have it");
  for (int c = 0; c < kRigCameras; ++c) {
    cv::Mat raw;
    if (!captures_[c].retrieve(raw) || raw.empty())
      throw std::runtime_error(std::string(rigCameraName(c)) + " camera ('" + sources_[c] +
                               "'): " + frameName(sources_[c], frames_) + " cannot be decoded");
    toGrey(raw, grey[c]);
  }
  ++frames_;
  return true;
}

std::vector<cv::Mat> readGreySequence(const std::string& source, const std::string& camera_name) {
  cv::VideoCapture cap;
  openSource(cap, source, camera_name);
  std::vector<cv::Mat> frames;
  cv::Mat raw;
  while (cap.read(raw) && !raw.empty()) {
    frames.emplace_back();
    toGrey(raw, frames.back());
  }
  return frames;
}

TrinocularCamera::TrinocularCamera(const CameraSources& sources, const RigCalibration& calibration,
                                   const RectificationOptions& options)
    : capture_(sources), calibration_(calibration) {
  calibration_.validate();
  rectification_ = rectifyRig(calibration_, options);
  for (int c = 0; c < kRigCameras; ++c)
    maps_[c] = rectificationMap(calibration_, rectification_, c);
}

TrinocularCamera::TrinocularCamera(const CameraSources& sources, const TrinocularRig& rig)
    : capture_(sources), rectified_sources_(true) {
  rectification_.rig = rig;
}

std::optional<TrinocularFrame> TrinocularCamera::capture(double stamp) {
  std::array<cv::Mat, kRigCameras> raw;
  const int index = capture_.frames();
  if (!capture_.read(raw)) return std::nullopt;
  TrinocularFrame frame;
  frame.stamp = stamp;
  try {
    rectify(raw, frame);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string(e.what()) + " (" + frameName("", index) + ")");
  }
  return frame;
}

void TrinocularCamera::rectify(const std::array<cv::Mat, kRigCameras>& raw,
                               TrinocularFrame& frame) const {
  cv::Mat* out[kRigCameras] = {&frame.reference, &frame.horizontal, &frame.vertical};
  cv::Mat grey;
  if (rectified_sources_) {
    const CameraIntrinsics& k = rectification_.rig.intrinsics;
    for (int c = 0; c < kRigCameras; ++c) {
      if (raw[c].cols != k.width || raw[c].rows != k.height)
        throw std::runtime_error(
            std::string(rigCameraName(c)) + " camera ('" + capture_.sources()[c] + "'): image is " +
            std::to_string(raw[c].cols) + "x" + std::to_string(raw[c].rows) + " px, the rig's is " +
            std::to_string(k.width) + "x" + std::to_string(k.height));
      toGrey(raw[c], *out[c]);
    }
    return;
  }
  for (int c = 0; c < kRigCameras; ++c) {
    const CameraCalibration& cam = calibration_.cameras[c];
    if (raw[c].cols != cam.width || raw[c].rows != cam.height)
      throw std::runtime_error(std::string(rigCameraName(c)) + " camera ('" +
                               capture_.sources()[c] + "'): image is " +
                               std::to_string(raw[c].cols) + "x" + std::to_string(raw[c].rows) +
                               " px, the calibration is for " + std::to_string(cam.width) + "x" +
                               std::to_string(cam.height));
    toGrey(raw[c], grey);
    cv::remap(grey, *out[c], maps_[c].x, maps_[c].y, cv::INTER_LINEAR, cv::BORDER_CONSTANT,
              cv::Scalar(0));
  }
}

}  // namespace coopmap
