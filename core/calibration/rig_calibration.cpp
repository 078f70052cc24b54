#include "core/calibration/rig_calibration.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/persistence.hpp>
#include <opencv2/imgproc.hpp>

#include "core/io/atomic_file.h"
#include "core/io/yaml_reader.h"

namespace coopmap {

namespace {
constexpr const char* kFormat = "coopmap-rig-calibration";
constexpr int kVersion = 1;

Eigen::Matrix3d toEigen(const cv::Matx33d& m) {
  Eigen::Matrix3d e;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) e(r, c) = m(r, c);
  return e;
}

cv::Matx33d toCv(const Eigen::Matrix3d& e) {
  cv::Matx33d m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m(r, c) = e(r, c);
  return m;
}

bool isRotation(const cv::Matx33d& R) {
  const Eigen::Matrix3d e = toEigen(R);
  return (e * e.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-6 &&
         std::abs(e.determinant() - 1.0) < 1e-6;
}

// Reads FileStorage nodes with errors that name the file and the field.
struct NodeReader {
  std::string file;

  [[noreturn]] void fail(const std::string& field, const std::string& expected) const {
    throw ConfigError(file + ": field '" + field + "': expected " + expected);
  }
  cv::FileNode child(const cv::FileNode& parent, const std::string& parent_name,
                     const std::string& key) const {
    const std::string field = parent_name.empty() ? key : parent_name + "." + key;
    if (!parent.isMap()) fail(parent_name, "a mapping");
    const cv::FileNode n = parent[key];
    if (n.empty() || n.isNone()) fail(field, "a value (missing)");
    return n;
  }
  double number(const cv::FileNode& parent, const std::string& parent_name, const std::string& key,
                double lo, double hi) const {
    const cv::FileNode n = child(parent, parent_name, key);
    const std::string field = parent_name.empty() ? key : parent_name + "." + key;
    if (!n.isReal() && !n.isInt())
      fail(field, "a number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    const double v = n.real();
    if (!(v >= lo && v <= hi))
      fail(field, "a number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                      std::to_string(v));
    return v;
  }
  cv::Mat matrix(const cv::FileNode& parent, const std::string& parent_name, const std::string& key,
                 int rows, int cols) const {
    const cv::FileNode n = child(parent, parent_name, key);
    const std::string field = parent_name + "." + key;
    const std::string what =
        "a " + std::to_string(rows) + "x" + std::to_string(cols) + " !!opencv-matrix of numbers";
    cv::Mat m;
    try {
      n >> m;
    } catch (const cv::Exception&) {
      fail(field, what);
    }
    if (m.empty() || m.total() != static_cast<size_t>(rows * cols) || m.channels() != 1)
      fail(field, what);
    m.convertTo(m, CV_64F);
    m = m.reshape(1, rows);
    for (double v : cv::Mat_<double>(m))
      if (!std::isfinite(v)) fail(field, what + " (finite)");
    return m;
  }
};
}  // namespace

const char* rigCameraName(int camera) {
  switch (camera) {
    case kReferenceCamera:
      return "reference";
    case kHorizontalCamera:
      return "horizontal";
    case kVerticalCamera:
      return "vertical";
    default:
      return "?";
  }
}

std::vector<cv::Point3f> Checkerboard::objectPoints() const {
  std::vector<cv::Point3f> points;
  points.reserve(static_cast<size_t>(cols) * rows);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      points.emplace_back(static_cast<float>(c * square), static_cast<float>(r * square), 0.0f);
  return points;
}

void Checkerboard::validate() const {
  auto bad = [](const std::string& field, const std::string& expected, double got) {
    throw std::invalid_argument("checkerboard: field '" + field + "': expected " + expected +
                                ", got " + std::to_string(got));
  };
  if (cols < 3 || cols > 100) bad("cols", "3..100 inner corners", cols);
  if (rows < 3 || rows > 100) bad("rows", "3..100 inner corners", rows);
  if (!(square > 0.0 && square < 10.0)) bad("square", "a side in (0, 10) m", square);
}

std::optional<std::vector<cv::Point2f>> findCheckerboard(const cv::Mat& image,
                                                         const Checkerboard& board) {
  cv::Mat grey;
  if (image.channels() == 1)
    grey = image;
  else
    cv::cvtColor(image, grey, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  std::vector<cv::Point2f> corners;
  const cv::Size pattern(board.cols, board.rows);
  if (!cv::findChessboardCorners(grey, pattern, corners,
                                 cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE))
    return std::nullopt;
  // The refinement window must stay inside the squares around each corner.
  double spacing = std::numeric_limits<double>::infinity();
  for (int r = 0; r < board.rows; ++r)
    for (int c = 0; c < board.cols; ++c) {
      const cv::Point2f& p = corners[static_cast<size_t>(r * board.cols + c)];
      if (c + 1 < board.cols)
        spacing = std::min(spacing, cv::norm(corners[r * board.cols + c + 1] - p));
      if (r + 1 < board.rows)
        spacing = std::min(spacing, cv::norm(corners[(r + 1) * board.cols + c] - p));
    }
  const int half = std::clamp(static_cast<int>(0.4 * spacing), 2, 11);
  cv::cornerSubPix(grey, corners, cv::Size(half, half), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100, 1e-4));
  // A board seen upside down is the same board turned by 180 degrees: the reversed order.
  if (corners.front().x + corners.front().y > corners.back().x + corners.back().y)
    std::reverse(corners.begin(), corners.end());
  return corners;
}

Eigen::Vector3d PartnerPose::position() const {
  const Eigen::Vector3d t(T[0], T[1], T[2]);
  return -toEigen(R).transpose() * t;
}

void RigCalibration::validate() const {
  auto bad = [](const std::string& field, const std::string& expected) {
    throw std::invalid_argument("rig calibration: field '" + field + "': expected " + expected);
  };
  for (int c = 0; c < kRigCameras; ++c) {
    const CameraCalibration& cam = cameras[c];
    const std::string name = rigCameraName(c);
    if (cam.width <= 0 || cam.height <= 0) bad(name + ".image_width", "a positive image size");
    if (!(cam.fx() > 0.0 && cam.fy() > 0.0)) bad(name + ".camera_matrix", "positive focal lengths");
  }
  for (int c : {kHorizontalCamera, kVerticalCamera}) {
    const std::string name = rigCameraName(c);
    if (!isRotation(partner(c).R)) bad(name + ".R", "a rotation matrix");
    if (!(cv::norm(partner(c).T) > 1e-6)) bad(name + ".T", "a non-zero baseline");
  }
}

RigCalibration calibrateRig(const std::vector<RigView>& views,
                            const std::array<cv::Size, kRigCameras>& sizes,
                            const Checkerboard& board) {
  board.validate();
  const std::vector<cv::Point3f> object = board.objectPoints();
  auto found = [&](const RigView& v, int c) { return v[c].size() == object.size(); };
  const cv::TermCriteria criteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 200, 1e-12);

  RigCalibration rig;
  rig.board = board;
  for (int c = 0; c < kRigCameras; ++c) {
    std::vector<std::vector<cv::Point3f>> obj;
    std::vector<std::vector<cv::Point2f>> img;
    for (const RigView& v : views)
      if (found(v, c)) obj.push_back(object), img.push_back(v[c]);
    if (obj.size() < 3)
      throw std::runtime_error(std::string("calibration: the ") + rigCameraName(c) +
                               " camera saw the whole board in " + std::to_string(obj.size()) +
                               " views; at least 3 are needed");
    cv::Mat K, D;
    std::vector<cv::Mat> rvecs, tvecs;
    CameraCalibration& cam = rig.cameras[c];
    cam.rms = cv::calibrateCamera(obj, img, sizes[c], K, D, rvecs, tvecs, 0, criteria);
    cam.width = sizes[c].width;
    cam.height = sizes[c].height;
    cam.camera_matrix = cv::Matx33d(K);
    for (int i = 0; i < 5; ++i) cam.distortion[i] = D.at<double>(i);
    cam.views = static_cast<int>(obj.size());
  }
  for (int p : {kHorizontalCamera, kVerticalCamera}) {
    std::vector<std::vector<cv::Point3f>> obj;
    std::vector<std::vector<cv::Point2f>> ref, partner;
    for (const RigView& v : views)
      if (found(v, kReferenceCamera) && found(v, p))
        obj.push_back(object), ref.push_back(v[kReferenceCamera]), partner.push_back(v[p]);
    if (obj.size() < 3)
      throw std::runtime_error(std::string("calibration: the reference and ") + rigCameraName(p) +
                               " cameras saw the whole board together in " +
                               std::to_string(obj.size()) + " views; at least 3 are needed");
    cv::Mat K0(rig.cameras[kReferenceCamera].camera_matrix),
        D0(rig.cameras[kReferenceCamera].distortion);
    cv::Mat K1(rig.cameras[p].camera_matrix), D1(rig.cameras[p].distortion);
    cv::Mat R, T, E, F;
    PartnerPose& pose = p == kHorizontalCamera ? rig.horizontal : rig.vertical;
    pose.rms = cv::stereoCalibrate(obj, ref, partner, K0, D0, K1, D1, sizes[kReferenceCamera], R, T,
                                   E, F, cv::CALIB_FIX_INTRINSIC, criteria);
    pose.R = cv::Matx33d(R);
    pose.T = cv::Vec3d(T.at<double>(0), T.at<double>(1), T.at<double>(2));
    pose.views = static_cast<int>(obj.size());
  }
  return rig;
}

RigRectification rectifyRig(const RigCalibration& calibration,
                            const RectificationOptions& options) {
  if (options.width < 0 || options.height < 0 || !(options.focal >= 0.0))
    throw std::invalid_argument("rectification: width, height and focal must be >= 0");
  const Eigen::Vector3d b_h = calibration.horizontal.position();
  const Eigen::Vector3d b_v = calibration.vertical.position();
  // Baseline directions pointing along the reference camera's +x and +y.
  Eigen::Vector3d a = b_h.normalized(), c = b_v.normalized();
  if (a.x() < 0) a = -a;
  if (c.y() < 0) c = -c;
  if (a.cross(c).norm() < 0.5)
    throw std::invalid_argument(
        "rectification: the horizontal and vertical baselines are nearly parallel; an L-rig "
        "needs them roughly perpendicular");
  // The orthonormal pair nearest to (a, c), sharing the error between them: both are turned
  // by the same angle about the normal of their plane.
  const Eigen::Vector3d m = (a + c).normalized(), n = (a - c).normalized();
  const Eigen::Vector3d x = (m + n).normalized(), y = (m - n).normalized();
  const Eigen::Vector3d z = x.cross(y);
  if (z.z() <= 0.0)
    throw std::invalid_argument(
        "rectification: the reference camera looks along the rig's plane; the cameras must "
        "face across it");
  Eigen::Matrix3d R_rect;
  R_rect.row(0) = x.transpose();
  R_rect.row(1) = y.transpose();
  R_rect.row(2) = z.transpose();

  RigRectification out;
  out.horizontal_exact = R_rect * b_h;
  out.vertical_exact = R_rect * b_v;
  out.orthogonality_error = std::abs(std::asin(std::clamp(a.dot(c), -1.0, 1.0)));
  out.rotations[kReferenceCamera] = toCv(R_rect);
  out.rotations[kHorizontalCamera] = toCv(R_rect * toEigen(calibration.horizontal.R).transpose());
  out.rotations[kVerticalCamera] = toCv(R_rect * toEigen(calibration.vertical.R).transpose());

  const CameraCalibration& ref = calibration.cameras[kReferenceCamera];
  double f = options.focal;
  if (f == 0.0) {
    for (const CameraCalibration& cam : calibration.cameras) f += cam.fx() + cam.fy();
    f /= 2.0 * kRigCameras;
  }
  CameraIntrinsics& k = out.rig.intrinsics;
  k.width = options.width > 0 ? options.width : ref.width;
  k.height = options.height > 0 ? options.height : ref.height;
  k.fx = k.fy = f;
  k.cx = 0.5 * (k.width - 1);
  k.cy = 0.5 * (k.height - 1);
  out.rig.horizontal_offset = {out.horizontal_exact.x(), 0.0, 0.0};
  out.rig.vertical_offset = {0.0, out.vertical_exact.y(), 0.0};
  if (options.equal_disparity_steps)
    k.fy = k.fx * std::abs(out.horizontal_exact.x()) / std::abs(out.vertical_exact.y());
  out.camera_matrix = cv::Matx33d(k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1);
  return out;
}

RectificationMap rectificationMap(const RigCalibration& calibration,
                                  const RigRectification& rectification, int camera) {
  const CameraCalibration& cam = calibration.cameras.at(static_cast<size_t>(camera));
  const CameraIntrinsics& k = rectification.rig.intrinsics;
  RectificationMap map;
  cv::initUndistortRectifyMap(
      cam.camera_matrix, cam.distortion, rectification.rotations.at(static_cast<size_t>(camera)),
      rectification.camera_matrix, cv::Size(k.width, k.height), CV_32FC1, map.x, map.y);
  return map;
}

void writeRigCalibration(const std::string& path, const RigCalibration& calibration,
                         const RectificationOptions& options) {
  calibration.validate();
  const RigRectification rect = rectifyRig(calibration, options);
  cv::FileStorage fs(".yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  fs << "format" << kFormat << "version" << kVersion;
  fs.writeComment(
      " Trinocular L-rig calibration (OpenCV pinhole model, distortion k1 k2 p1 p2 k3).\n"
      " Partners: R, T as cv::stereoCalibrate gives them: x_partner = R x_reference + T (m).");
  fs << "board"
     << "{"
     << "cols" << calibration.board.cols << "rows" << calibration.board.rows << "square"
     << calibration.board.square << "}";
  for (int c = 0; c < kRigCameras; ++c) {
    const CameraCalibration& cam = calibration.cameras[c];
    fs << rigCameraName(c) << "{";
    fs << "image_width" << cam.width << "image_height" << cam.height;
    fs << "camera_matrix" << cv::Mat(cam.camera_matrix);
    fs << "distortion_coefficients" << cv::Mat(cam.distortion).reshape(1, 1);
    fs << "rms" << cam.rms << "views" << cam.views;
    if (c != kReferenceCamera) {
      const PartnerPose& p = calibration.partner(c);
      fs << "R" << cv::Mat(p.R) << "T" << cv::Mat(p.T) << "stereo_rms" << p.rms << "stereo_views"
         << p.views;
    }
    fs << "}";
  }
  fs.writeComment(
      " Derived from the above when the file is read (written for other tools): the common\n"
      " camera matrix and each camera's rectifying rotation (the R of\n"
      " cv::initUndistortRectifyMap), the partners' offsets in the rectified frame (m).");
  fs << "rectified"
     << "{"
     << "image_width" << rect.rig.intrinsics.width << "image_height" << rect.rig.intrinsics.height
     << "camera_matrix" << cv::Mat(rect.camera_matrix);
  for (int c = 0; c < kRigCameras; ++c)
    fs << std::string("R_") + rigCameraName(c) << cv::Mat(rect.rotations[c]);
  const Eigen::Vector3d& h = rect.horizontal_exact;
  const Eigen::Vector3d& v = rect.vertical_exact;
  fs << "horizontal_offset" << cv::Mat(cv::Vec3d(h.x(), h.y(), h.z())) << "vertical_offset"
     << cv::Mat(cv::Vec3d(v.x(), v.y(), v.z())) << "}";
  writeFileAtomic(path, fs.releaseAndGetString());
}

RigCalibration readRigCalibration(const std::string& path) {
  std::string text;
  try {
    text = readFile(path);
  } catch (const std::exception&) {
    throw ConfigError(path + ": cannot open calibration file");
  }
  cv::FileStorage fs;
  try {
    fs.open(text, cv::FileStorage::READ | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  } catch (const cv::Exception& e) {
    throw ConfigError(path + ": not an OpenCV YAML calibration file: " + e.err);
  }
  if (!fs.isOpened()) throw ConfigError(path + ": not an OpenCV YAML calibration file");
  const NodeReader r{path};
  const cv::FileNode root = fs.root();
  const cv::FileNode format = r.child(root, "", "format");
  if (!format.isString() || format.string() != kFormat)
    r.fail("format", std::string("'") + kFormat + "'");
  const int version = static_cast<int>(r.number(root, "", "version", 1, 1e9));
  if (version != kVersion)
    r.fail("version", std::to_string(kVersion) + ", got " + std::to_string(version));

  RigCalibration rig;
  const cv::FileNode board = r.child(root, "", "board");
  rig.board.cols = static_cast<int>(r.number(board, "board", "cols", 3, 100));
  rig.board.rows = static_cast<int>(r.number(board, "board", "rows", 3, 100));
  rig.board.square = r.number(board, "board", "square", 1e-6, 10.0);
  for (int c = 0; c < kRigCameras; ++c) {
    const std::string name = rigCameraName(c);
    const cv::FileNode node = r.child(root, "", name);
    CameraCalibration& cam = rig.cameras[c];
    cam.width = static_cast<int>(r.number(node, name, "image_width", 1, 100000));
    cam.height = static_cast<int>(r.number(node, name, "image_height", 1, 100000));
    cam.camera_matrix = cv::Matx33d(r.matrix(node, name, "camera_matrix", 3, 3));
    if (!(cam.fx() > 0.0 && cam.fy() > 0.0))
      r.fail(name + ".camera_matrix", "positive focal lengths fx, fy");
    const cv::Mat d = r.matrix(node, name, "distortion_coefficients", 1, 5);
    for (int i = 0; i < 5; ++i) cam.distortion[i] = d.at<double>(i);
    cam.rms = r.number(node, name, "rms", 0.0, 1e6);
    cam.views = static_cast<int>(r.number(node, name, "views", 0, 1e9));
    if (c != kReferenceCamera) {
      PartnerPose& p = c == kHorizontalCamera ? rig.horizontal : rig.vertical;
      p.R = cv::Matx33d(r.matrix(node, name, "R", 3, 3));
      if (!isRotation(p.R)) r.fail(name + ".R", "a rotation matrix");
      const cv::Mat t = r.matrix(node, name, "T", 3, 1);
      p.T = cv::Vec3d(t.at<double>(0), t.at<double>(1), t.at<double>(2));
      if (!(cv::norm(p.T) > 1e-6)) r.fail(name + ".T", "a non-zero baseline (m)");
      p.rms = r.number(node, name, "stereo_rms", 0.0, 1e6);
      p.views = static_cast<int>(r.number(node, name, "stereo_views", 0, 1e9));
    }
  }
  return rig;
}

}  // namespace coopmap
