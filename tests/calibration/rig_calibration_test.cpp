// Cameras, calibration and rectification against a rig the simulator knows: checkerboard
// views rendered through three distorted cameras are calibrated (`coopmap calibrate`'s
// code), and the camera driver's rectified images of a rendered scene give the trinocular
// matcher the true disparity.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/calibration/rig_calibration.h"
#include "core/io/yaml_reader.h"
#include "core/stereo/trinocular_matcher.h"
#include "robots/camera/calibrate_rig.h"
#include "robots/camera/trinocular_camera.h"
#include "sim/render/renderer.h"
#include "sim/sensors/lens_distortion.h"
#include "sim/world/world.h"

namespace coopmap {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr int kSupersample = 3;

// The true rig: three slightly different distorted cameras, partners a little off their
// nominal 0.10 m offsets and turned by fractions of a degree.
struct TrueCamera {
  CameraIntrinsics k;
  sim::LensDistortion d;
  Eigen::Isometry3d X_RC = Eigen::Isometry3d::Identity();  // camera in the reference frame
};

CameraIntrinsics intrinsics(double fx, double fy, double cx, double cy) {
  CameraIntrinsics k;
  k.width = 320;
  k.height = 240;
  k.fx = fx, k.fy = fy, k.cx = cx, k.cy = cy;
  return k;
}

Eigen::Isometry3d pose(const Eigen::Vector3d& rvec, const Eigen::Vector3d& position) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  if (rvec.norm() > 0) X.linear() = Eigen::AngleAxisd(rvec.norm(), rvec.normalized()).matrix();
  X.translation() = position;
  return X;
}

std::array<TrueCamera, kRigCameras> trueRig() {
  std::array<TrueCamera, kRigCameras> rig;
  rig[kReferenceCamera].k = intrinsics(200.0, 201.0, 161.3, 118.7);
  rig[kReferenceCamera].d = {-0.22, 0.06, 0.0008, -0.0006, -0.005};
  rig[kHorizontalCamera].k = intrinsics(203.0, 203.5, 158.2, 121.1);
  rig[kHorizontalCamera].d = {-0.19, 0.04, -0.0005, 0.0004, 0.0};
  rig[kHorizontalCamera].X_RC = pose({0.004, -0.007, 0.003}, {0.1004, 0.0012, -0.0015});
  rig[kVerticalCamera].k = intrinsics(198.0, 198.8, 160.9, 119.6);
  rig[kVerticalCamera].d = {-0.25, 0.08, 0.0003, 0.0009, -0.01};
  rig[kVerticalCamera].X_RC = pose({-0.005, 0.003, 0.006}, {-0.0009, -0.0996, 0.0011});
  return rig;
}

sim::TextureSpec texture(const std::string& name, sim::TextureType type, double mean,
                         double contrast, double feature) {
  sim::TextureSpec t;
  t.name = name;
  t.type = type;
  t.tile = 2.0;
  t.feature = feature;
  t.mean = mean;
  t.contrast = contrast;
  t.seed = 7;
  return t;
}

// A checkerboard (9x6 inner corners, 40 mm squares) 1.2 m up, facing +x, on a plain floor.
sim::World boardWorld() {
  sim::World w;
  w.name = "board";
  w.textures["grey"] = texture("grey", sim::TextureType::kUniform, 110, 0, 0.05);
  w.floor_texture = "grey";
  w.floor_min = {-5, -5};
  w.floor_max = {5, 5};
  sim::TargetSpec t;
  t.center = {0.0, 0.0, 1.2};
  t.squares_x = 10;
  t.squares_y = 7;
  t.square = 0.04;
  w.targets.push_back(t);
  return w;
}

// A textured wall 2.6 m ahead of the rig (facing +x) and a box 1.6 m ahead, for stereo.
sim::World sceneWorld() {
  sim::World w;
  w.name = "scene";
  w.textures["carpet"] = texture("carpet", sim::TextureType::kNoise, 105, 30, 0.03);
  w.textures["wall"] = texture("wall", sim::TextureType::kNoise, 128, 60, 0.02);
  w.textures["poster"] = texture("poster", sim::TextureType::kPosters, 128, 70, 0.04);
  w.floor_texture = "carpet";
  w.floor_min = {-5, -5};
  w.floor_max = {5, 5};
  w.walls.push_back({{-2.6, -4.0}, {-2.6, 4.0}, 0.1, 3.0, "wall"});
  sim::SolidBox box;
  box.center = {-1.8, 0.25};
  box.size = {0.4, 0.5, 1.5};
  box.texture = "poster";
  w.boxes.push_back(box);
  return w;
}

// A camera at `eye` looking at `target`, world z up, turned by `roll` about its axis.
Eigen::Isometry3d lookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target, double roll) {
  const Eigen::Vector3d z = (target - eye).normalized();
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear().col(0) = x;
  X.linear().col(1) = y;
  X.linear().col(2) = z;
  X.linear() = X.linear() * Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()).matrix();
  X.translation() = eye;
  return X;
}

// Renders the three distorted cameras of the true rig with the reference camera at X_WR.
class RigRenderer {
 public:
  explicit RigRenderer(const sim::World& world) : rig_(trueRig()) {
    std::vector<std::pair<CameraIntrinsics, sim::LensDistortion>> cams;
    for (const TrueCamera& c : rig_) cams.emplace_back(c.k, c.d);
    render_k_ = sim::LensDistorter::renderIntrinsicsFor(cams, kSupersample);
    renderer_ = std::make_unique<sim::Renderer>(world, render_k_);
    for (const TrueCamera& c : rig_) distorters_.emplace_back(c.k, c.d, render_k_, kSupersample);
  }
  std::array<cv::Mat, kRigCameras> render(const Eigen::Isometry3d& X_WR) {
    std::vector<Eigen::Isometry3d> poses;
    for (const TrueCamera& c : rig_) poses.push_back(X_WR * c.X_RC);
    std::array<cv::Mat, kRigCameras> ideal, out;
    renderer_->renderViews(poses, {}, {}, {&ideal[0], &ideal[1], &ideal[2]});
    for (int c = 0; c < kRigCameras; ++c) distorters_[c].apply(ideal[c], out[c]);
    return out;
  }
  const std::array<TrueCamera, kRigCameras>& rig() const { return rig_; }

 private:
  std::array<TrueCamera, kRigCameras> rig_;
  CameraIntrinsics render_k_;
  std::unique_ptr<sim::Renderer> renderer_;
  std::vector<sim::LensDistorter> distorters_;
};

// Whether every board corner is inside each true camera's image (8 px in) and within its
// well-behaved field of view.
bool boardVisible(const std::array<TrueCamera, kRigCameras>& rig, const sim::TargetSpec& target,
                  const Eigen::Isometry3d& X_WR) {
  for (const TrueCamera& c : rig) {
    const Eigen::Isometry3d X_CW = (X_WR * c.X_RC).inverse();
    std::vector<cv::Point3d> points;
    // Every corner of every square (the detector needs the outer squares whole).
    for (int j = -1; j < target.squares_y; ++j)
      for (int i = -1; i < target.squares_x; ++i) {
        const Eigen::Vector3d p = X_CW * target.cornerInWorld(i, j);
        if (p.z() <= 0.1 || std::hypot(p.x() / p.z(), p.y() / p.z()) > 1.4) return false;
        points.emplace_back(p.x(), p.y(), p.z());
      }
    std::vector<cv::Point2d> px;
    cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0),
                      cv::Matx33d(c.k.fx, 0, c.k.cx, 0, c.k.fy, c.k.cy, 0, 0, 1),
                      cv::Vec<double, 5>(c.d.k1, c.d.k2, c.d.p1, c.d.p2, c.d.k3), px);
    for (const cv::Point2d& p : px)
      if (p.x < 4 || p.y < 4 || p.x > c.k.width - 5 || p.y > c.k.height - 5) return false;
  }
  // The board must face the reference camera.
  const Eigen::Vector3d normal = -target.rotation().col(2);
  return normal.dot(X_WR.translation() - target.center) > 0;
}

void writeImage(const std::string& path, const cv::Mat& image) {
  ASSERT_TRUE(cv::imwrite(path, image)) << path;
}

const char* kPrefix[kRigCameras] = {"ref", "hor", "ver"};

// A fresh temporary folder of this process (CTest runs tests in parallel processes).
std::string tempDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

// Everything the tests share: views written, calibration run once.
struct Shared {
  std::string dir;
  std::array<std::string, kRigCameras> board_patterns, scene_patterns;
  CalibrateResult calibration;
  std::string calibration_file;
  std::vector<Eigen::Isometry3d> scene_poses;
};

class RigCalibrationTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    shared_ = new Shared;
    Shared& s = *shared_;
    s.dir = tempDir("coopmap_rig_calibration_test");
    for (int c = 0; c < kRigCameras; ++c) {
      s.board_patterns[c] = s.dir + "/board_" + kPrefix[c] + "_%04d.png";
      s.scene_patterns[c] = s.dir + "/scene_" + kPrefix[c] + "_%04d.png";
    }
    // 20 checkerboard views from random poses in front of the board (seeded).
    const sim::World board = boardWorld();
    RigRenderer renderer(board);
    const sim::TargetSpec& target = board.targets.front();
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int views = 0;
    for (int tries = 0; tries < 5000 && views < 25; ++tries) {
      const double distance = 0.45 + 0.2 * (u(rng) + 1.0);
      const double yaw = 0.7 * u(rng), elevation = 0.6 * u(rng);
      const Eigen::Vector3d eye =
          target.center + distance * Eigen::Vector3d(std::cos(elevation) * std::cos(yaw),
                                                     std::cos(elevation) * std::sin(yaw),
                                                     std::sin(elevation));
      const Eigen::Vector3d aim = target.center + Eigen::Vector3d(0, 0.25 * u(rng), 0.2 * u(rng));
      const Eigen::Isometry3d X_WR = lookAt(eye, aim, 0.35 * u(rng));
      if (!boardVisible(renderer.rig(), target, X_WR)) continue;
      const auto images = renderer.render(X_WR);
      for (int c = 0; c < kRigCameras; ++c) {
        char name[64];
        std::snprintf(name, sizeof name, s.board_patterns[c].c_str(), views);
        writeImage(name, images[c]);
      }
      ++views;
    }
    ASSERT_EQ(views, 25) << "not enough views with the board in all three cameras";

    CalibrateOptions options;
    options.sources = s.board_patterns;
    options.board = "9x6";
    options.square = 0.04;
    options.out_file = s.calibration_file = s.dir + "/calib.yaml";
    s.calibration = runCalibrate(options);
    std::printf("%s", s.calibration.report.c_str());

    // Three frames of a textured scene from a rig 1 m up, looking along -x.
    const sim::World scene = sceneWorld();
    RigRenderer scene_renderer(scene);
    for (int f = 0; f < 3; ++f) {
      const Eigen::Vector3d eye(0.0, -0.1 + 0.1 * f, 1.0);
      s.scene_poses.push_back(lookAt(eye, eye + Eigen::Vector3d(-1.0, 0.05 * (f - 1), -0.1), 0.0));
      const auto images = scene_renderer.render(s.scene_poses.back());
      for (int c = 0; c < kRigCameras; ++c) {
        char name[64];
        std::snprintf(name, sizeof name, s.scene_patterns[c].c_str(), f);
        writeImage(name, images[c]);
      }
    }
  }
  static void TearDownTestSuite() {
    if (shared_) fs::remove_all(shared_->dir);
    delete shared_;
    shared_ = nullptr;
  }
  static Shared* shared_;
};
Shared* RigCalibrationTest::shared_ = nullptr;

TEST_F(RigCalibrationTest, RecoversFocalLengthsWithinHalfAPercent) {
  const auto truth = trueRig();
  const RigCalibration& cal = shared_->calibration.calibration;
  for (int c = 0; c < kRigCameras; ++c) {
    const CameraCalibration& cam = cal.cameras[c];
    const CameraIntrinsics& k = truth[c].k;
    const double efx = std::abs(cam.fx() / k.fx - 1.0), efy = std::abs(cam.fy() / k.fy - 1.0);
    std::printf(
        "%s: fx error %.3f %%, fy error %.3f %%, principal point off (%.2f, %.2f) px, "
        "k1 %.4f (true %.4f), RMS %.3f px over %d views\n",
        rigCameraName(c), 100 * efx, 100 * efy, cam.cx() - k.cx, cam.cy() - k.cy, cam.distortion[0],
        truth[c].d.k1, cam.rms, cam.views);
    // The detector misses the odd steep view; the calibration needs most of them.
    EXPECT_GE(shared_->calibration.found[c], 20) << rigCameraName(c);
    EXPECT_LT(efx, 0.005) << rigCameraName(c);
    EXPECT_LT(efy, 0.005) << rigCameraName(c);
    EXPECT_LT(std::abs(cam.cx() - k.cx), 2.0) << rigCameraName(c);
    EXPECT_LT(std::abs(cam.cy() - k.cy), 2.0) << rigCameraName(c);
    EXPECT_LT(cam.rms, 0.5) << rigCameraName(c);
    EXPECT_GT(cam.rms, 0.0) << rigCameraName(c);
  }
}

TEST_F(RigCalibrationTest, RecoversBaselinesWithinOneMillimetre) {
  const auto truth = trueRig();
  const RigCalibration& cal = shared_->calibration.calibration;
  for (int c : {kHorizontalCamera, kVerticalCamera}) {
    const Eigen::Vector3d est = cal.partner(c).position();
    const Eigen::Vector3d& tru = truth[c].X_RC.translation();
    const Eigen::AngleAxisd rot_error(Eigen::Matrix3d(
        Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(cal.partner(c).R.val) *
        truth[c].X_RC.linear()));
    std::printf(
        "%s: baseline %.2f mm (true %.2f mm), position error %.3f mm, rotation error "
        "%.4f deg, stereo RMS %.3f px\n",
        rigCameraName(c), 1000 * est.norm(), 1000 * tru.norm(), 1000 * (est - tru).norm(),
        rot_error.angle() * 180 / M_PI, cal.partner(c).rms);
    EXPECT_LT((est - tru).norm(), 0.001) << rigCameraName(c);
    EXPECT_LT(rot_error.angle(), 0.1 * M_PI / 180) << rigCameraName(c);
    EXPECT_LT(cal.partner(c).rms, 0.5) << rigCameraName(c);
  }
}

TEST_F(RigCalibrationTest, CalibrationFileReadsBackExactly) {
  const RigCalibration& cal = shared_->calibration.calibration;
  const RigCalibration back = readRigCalibration(shared_->calibration_file);
  for (int c = 0; c < kRigCameras; ++c) {
    EXPECT_EQ(cv::norm(back.cameras[c].camera_matrix - cal.cameras[c].camera_matrix), 0.0);
    EXPECT_EQ(cv::norm(back.cameras[c].distortion - cal.cameras[c].distortion), 0.0);
    EXPECT_EQ(back.cameras[c].rms, cal.cameras[c].rms);
    EXPECT_EQ(back.cameras[c].width, 320);
  }
  for (int c : {kHorizontalCamera, kVerticalCamera}) {
    EXPECT_EQ(cv::norm(back.partner(c).R - cal.partner(c).R), 0.0);
    EXPECT_EQ(cv::norm(back.partner(c).T - cal.partner(c).T), 0.0);
  }
  EXPECT_EQ(back.board.cols, 9);
  EXPECT_EQ(back.board.rows, 6);
}

// The rectified images of the driver give the matcher the true disparity of the scene
// (truth: the depth rendered by a pinhole camera at the rectified reference camera).
TEST_F(RigCalibrationTest, DriverRectifiesSoTheMatcherFindsTheTrueDisparity) {
  const Shared& s = *shared_;
  const RigCalibration cal = readRigCalibration(s.calibration_file);
  TrinocularCamera camera(s.scene_patterns, cal);
  const TrinocularRig& rig = camera.rig();
  EXPECT_EQ(rig.horizontal_offset.y(), 0.0);
  EXPECT_EQ(rig.vertical_offset.x(), 0.0);
  EXPECT_NEAR(rig.horizontal_offset.x(), 0.1004, 0.001);
  EXPECT_NEAR(rig.vertical_offset.y(), -0.0996, 0.001);

  StereoConfig config;
  config.num_disparities = 32;
  TrinocularMatcher matcher(rig, config);
  // Truth: a pinhole camera with the rectified intrinsics, turned as the rectified frame.
  Eigen::Matrix3d R_rect;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R_rect(r, c) = camera.rectification().rotations[0](r, c);
  Eigen::Isometry3d X_R_rect = Eigen::Isometry3d::Identity();
  X_R_rect.linear() = R_rect.transpose();
  sim::Renderer truth_renderer(sceneWorld(), rig.intrinsics);

  // The raw (distorted, unrectified) images with the nominal rig, for comparison.
  TrinocularRig nominal;
  nominal.intrinsics = trueRig()[0].k;
  TrinocularMatcher raw_matcher(nominal, config);
  RawTrinocularCapture raw_capture(s.scene_patterns);

  int frames = 0;
  while (auto frame = camera.capture(frames * 0.5)) {
    ASSERT_EQ(frame->reference.type(), CV_8UC1);
    ASSERT_EQ(frame->reference.cols, rig.intrinsics.width);
    EXPECT_EQ(frame->stamp, frames * 0.5);
    cv::Mat disparity, grey, depth;
    matcher.compute(frame->reference, frame->horizontal, frame->vertical, disparity);
    truth_renderer.render(s.scene_poses[frames] * X_R_rect, {}, {}, grey, &depth);
    auto score = [&](const cv::Mat& d, double fb, double* median) {
      std::vector<double> errors;
      for (int y = 0; y < d.rows; ++y)
        for (int x = 0; x < d.cols; ++x) {
          const float z = depth.at<float>(y, x), v = d.at<float>(y, x);
          if (z > 0 && v != kInvalidDisparity) errors.push_back(std::abs(v - fb / z));
        }
      std::sort(errors.begin(), errors.end());
      *median = errors.empty() ? 1e9 : errors[errors.size() / 2];
      const auto within = std::lower_bound(errors.begin(), errors.end(), 1.0) - errors.begin();
      return std::pair<double, double>(
          errors.empty() ? 0.0 : static_cast<double>(within) / errors.size(),
          static_cast<double>(errors.size()) / (d.rows * d.cols));
    };
    double median = 0.0;
    const auto [within, density] = score(disparity, matcher.focalBaseline(), &median);
    std::array<cv::Mat, kRigCameras> raw;
    ASSERT_TRUE(raw_capture.read(raw));
    cv::Mat raw_disparity;
    raw_matcher.compute(raw[0], raw[1], raw[2], raw_disparity);
    double raw_median = 0.0;
    const auto [raw_within, raw_density] =
        score(raw_disparity, raw_matcher.focalBaseline(), &raw_median);
    std::printf(
        "frame %d rectified: %.1f %% valid, %.1f %% of them within 1 px, median error "
        "%.3f px; raw images: %.1f %% valid, %.1f %% within 1 px, median %.3f px\n",
        frames, 100 * density, 100 * within, median, 100 * raw_density, 100 * raw_within,
        raw_median);
    EXPECT_GT(density, 0.4) << "frame " << frames;
    EXPECT_GT(within, 0.95) << "frame " << frames;
    EXPECT_LT(median, 0.25) << "frame " << frames;
    ++frames;
  }
  EXPECT_EQ(frames, 3);
}

TEST(CameraDriverTest, MissingSourceNamesTheCameraAndTheFile) {
  const std::string dir = tempDir("coopmap_camera_driver_test");
  const cv::Mat image(240, 320, CV_8UC1, cv::Scalar(100));
  for (int f = 0; f < 3; ++f)
    for (const char* p : {"ref", "hor", "ver"}) {
      if (std::string(p) == "ver" && f == 2) continue;  // the vertical camera lacks frame 2
      char name[64];
      std::snprintf(name, sizeof name, "/%s_%04d.png", p, f);
      writeImage(dir + name, image);
    }
  const CameraSources good = {dir + "/ref_%04d.png", dir + "/hor_%04d.png", dir + "/ver_%04d.png"};
  CameraSources missing = good;
  missing[2] = dir + "/nothing_%04d.png";
  try {
    RawTrinocularCapture capture(missing);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("vertical camera"));
    EXPECT_THAT(e.what(), HasSubstr(dir + "/nothing_0000.png"));
  }
  missing[2] = dir + "/video.avi";
  try {
    RawTrinocularCapture capture(missing);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("vertical camera: cannot open '" + dir + "/video.avi'"));
  }

  RawTrinocularCapture capture(good);
  std::array<cv::Mat, kRigCameras> grey;
  EXPECT_TRUE(capture.read(grey));
  EXPECT_EQ(grey[1].type(), CV_8UC1);
  EXPECT_EQ(cv::norm(grey[1], image, cv::NORM_INF), 0.0);
  EXPECT_TRUE(capture.read(grey));
  try {
    capture.read(grey);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("vertical camera"));
    EXPECT_THAT(e.what(), HasSubstr("frame 2"));
    EXPECT_THAT(e.what(), HasSubstr("ver_0002.png"));
  }
  fs::remove_all(dir);
}

TEST(CalibrationFileTest, BadFilesAreReportedWithTheFileAndTheField) {
  const std::string dir = tempDir("coopmap_calibration_file_test");
  auto error = [&](const std::string& name, const std::string& text) -> std::string {
    const std::string path = dir + "/" + name;
    if (!text.empty()) std::ofstream(path) << text;
    try {
      readRigCalibration(path);
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(error("absent.yaml", ""), dir + "/absent.yaml: cannot open calibration file");
  EXPECT_THAT(error("garbage.yaml", "%YAML:1.0\n---\nformat: [unclosed\n"),
              HasSubstr(dir + "/garbage.yaml: not an OpenCV YAML calibration file"));
  EXPECT_EQ(error("format.yaml", "%YAML:1.0\n---\nformat: other\nversion: 1\n"),
            dir + "/format.yaml: field 'format': expected 'coopmap-rig-calibration'");

  // A good file with one field broken.
  RigCalibration cal;
  for (CameraCalibration& c : cal.cameras) {
    c.width = 320, c.height = 240;
    c.camera_matrix = cv::Matx33d(200, 0, 160, 0, 200, 120, 0, 0, 1);
  }
  cal.horizontal.T = {-0.1, 0, 0};
  cal.vertical.T = {0, 0.1, 0};
  const std::string good = dir + "/good.yaml";
  writeRigCalibration(good, cal);
  EXPECT_EQ(readRigCalibration(good).vertical.T[1], 0.1);
  std::ifstream in(good);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t at = text.find("stereo_rms", text.find("vertical:"));
  ASSERT_NE(at, std::string::npos);
  std::string broken = text;
  broken.replace(at, 10, "stereo_rmz");
  EXPECT_EQ(error("missing.yaml", broken),
            dir + "/missing.yaml: field 'vertical.stereo_rms': expected a value (missing)");
  broken = text;
  const size_t r = text.find("R: !!opencv-matrix", text.find("horizontal:"));
  broken.replace(text.find("data: [", r), 7, "data: [ 2.,");
  EXPECT_THAT(error("rotation.yaml", broken),
              HasSubstr(dir + "/rotation.yaml: field 'horizontal.R': expected a 3x3"));
  fs::remove_all(dir);
}

TEST(CalibrateCommandTest, BoardOptionIsChecked) {
  EXPECT_EQ(parseBoard("9x6", 0.04).cols, 9);
  EXPECT_EQ(parseBoard("9x6", 0.04).rows, 6);
  for (const char* bad : {"9", "9x", "x6", "9x6x", "nine", "2x6"})
    EXPECT_THROW(parseBoard(bad, 0.04), std::invalid_argument) << bad;
  try {
    parseBoard("9by6", 0.04);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("--board: expected COLSxROWS"));
    EXPECT_THAT(e.what(), HasSubstr("'9by6'"));
  }
}

}  // namespace
}  // namespace coopmap
