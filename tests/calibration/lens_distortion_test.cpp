// The simulator's lens distortion follows OpenCV's model exactly, checkerboard targets load
// from world files and render where the world says.
#include <cmath>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include "core/calibration/rig_calibration.h"
#include "core/io/yaml_reader.h"
#include "sim/render/renderer.h"
#include "sim/sensors/lens_distortion.h"
#include "sim/world/world.h"

namespace coopmap::sim {
namespace {

using ::testing::HasSubstr;

CameraIntrinsics camera() {
  CameraIntrinsics k;
  k.width = 320, k.height = 240, k.fx = 200, k.fy = 202, k.cx = 161.3, k.cy = 118.7;
  return k;
}

TEST(LensDistortionTest, EveryPixelLooksAlongTheRayOpenCvProjectsThere) {
  const LensDistortion d{-0.25, 0.08, 0.0009, -0.0007, -0.01};
  const CameraIntrinsics k = camera();
  const CameraIntrinsics render = LensDistorter::renderIntrinsicsFor({{k, d}}, 3);
  EXPECT_EQ(render.fx, 3 * 202.0);
  const LensDistorter distorter(k, d, render, 3);
  std::vector<cv::Point3d> rays;
  std::vector<cv::Point2d> pixels;
  for (int v = 0; v < k.height; v += 7)
    for (int u = 0; u < k.width; u += 7) {
      const cv::Point2f p = distorter.renderPixel(u, v);
      // Inside the render, away from its edge.
      EXPECT_GT(p.x, 3.0f);
      EXPECT_GT(p.y, 3.0f);
      EXPECT_LT(p.x, render.width - 4.0f);
      EXPECT_LT(p.y, render.height - 4.0f);
      rays.emplace_back((p.x - render.cx) / render.fx, (p.y - render.cy) / render.fy, 1.0);
      pixels.emplace_back(u, v);
    }
  std::vector<cv::Point2d> projected;
  cv::projectPoints(rays, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0),
                    cv::Matx33d(k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1),
                    cv::Vec<double, 5>(d.k1, d.k2, d.p1, d.p2, d.k3), projected);
  double worst = 0.0;
  for (size_t i = 0; i < pixels.size(); ++i)
    worst = std::max(worst, cv::norm(projected[i] - pixels[i]));
  EXPECT_LT(worst, 2e-3);  // px; float maps
  // Barrel distortion: the corner pixel looks farther out than a pinhole's would.
  const cv::Point2f corner = distorter.renderPixel(0, 0);
  EXPECT_GT((render.cx - corner.x) / render.fx, k.cx / k.fx + 0.1);
}

TEST(LensDistortionTest, WithoutDistortionOrSupersamplingTheImageIsTheRender) {
  const CameraIntrinsics k = camera();
  CameraIntrinsics render = k;  // the same camera with a 10 px margin
  render.width += 20, render.height += 20, render.cx += 10, render.cy += 10;
  const LensDistorter distorter(k, {}, render, 1);
  cv::Mat ideal(render.height, render.width, CV_8UC1);
  cv::randu(ideal, 0, 256);
  cv::Mat out;
  distorter.apply(ideal, out);
  EXPECT_EQ(cv::norm(out, ideal(cv::Rect(10, 10, k.width, k.height)), cv::NORM_INF), 0.0);
  // The render intrinsics for an undistorted camera: its own focal length, the whole image.
  const CameraIntrinsics fitted = LensDistorter::renderIntrinsicsFor({{k, {}}}, 1);
  EXPECT_EQ(fitted.fx, k.fy);
  EXPECT_GE(fitted.width, k.width);
}

TEST(LensDistortionTest, BadCoefficientsAreNamed) {
  LensDistortion d;
  d.p2 = 0.5;
  try {
    d.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("field 'p2'"));
  }
  EXPECT_THROW(LensDistorter::renderIntrinsicsFor({{camera(), {}}}, 2), std::invalid_argument);
}

std::string worldWithTargets(const std::string& targets) {
  return "name: t\n"
         "textures:\n"
         "  a: {type: uniform, tile: 1.0}\n"
         "floor: {min: [-3, -3], max: [3, 3], texture: a}\n"
         "walls: []\n"
         "home_base:\n"
         "  corners:\n"
         "    - {position: [1, 1], heading_deg: 0}\n"
         "    - {position: [1, 2], heading_deg: 0}\n"
         "  texture: a\n"
         "robots:\n"
         "  - name: r1\n"
         "    model: " COOPMAP_SOURCE_DIR
         "/robots/b14/b14.yaml\n"
         "    start: {position: [0, 0]}\n"
         "targets:\n" +
         targets;
}

TEST(CheckerboardTargetTest, LoadsAndRendersWhereTheWorldSays) {
  const World w = parseWorld(
      worldWithTargets("  - {center: [0, 0, 1.2], squares: [10, 7], square: 0.05, yaw_deg: "
                       "20, pitch_deg: -10, roll_deg: 5}\n"),
      "t.yaml");
  ASSERT_EQ(w.targets.size(), 1u);
  const TargetSpec& t = w.targets[0];
  EXPECT_EQ(t.squares_x, 10);
  EXPECT_EQ(t.squares_y, 7);
  EXPECT_NEAR(t.yaw, 20 * M_PI / 180, 1e-12);
  // The board frame is a rotation; its first corner is up and to the left seen from the
  // front.
  EXPECT_NEAR((t.rotation() * t.rotation().transpose() - Eigen::Matrix3d::Identity()).norm(), 0,
              1e-12);
  EXPECT_NEAR(t.rotation().determinant(), 1.0, 1e-12);

  // Seen from 0.9 m in front, the detector finds the corners where they project.
  CameraIntrinsics k = camera();
  k.fx = k.fy = 300;
  Renderer renderer(w, k);
  const Eigen::Vector3d normal = -t.rotation().col(2);
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  X_WC.linear() = t.rotation();  // looking into the board, rows horizontal in the image
  X_WC.translation() = t.center + 0.9 * normal;
  cv::Mat grey;
  renderer.render(X_WC, {}, {}, grey);
  const Checkerboard board{9, 6, 0.05};
  const auto corners = findCheckerboard(grey, board);
  ASSERT_TRUE(corners.has_value());
  double worst = 0.0;
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 9; ++i) {
      const Eigen::Vector3d p = X_WC.inverse() * t.cornerInWorld(i, j);
      const cv::Point2d expected(k.fx * p.x() / p.z() + k.cx, k.fy * p.y() / p.z() + k.cy);
      worst = std::max(worst, cv::norm(cv::Point2d((*corners)[j * 9 + i]) - expected));
    }
  EXPECT_LT(worst, 0.3);  // px, aliased edges (no supersampling here)
}

TEST(CheckerboardTargetTest, BadTargetIsReportedWithLineAndField) {
  try {
    parseWorld(worldWithTargets("  - {center: [0, 0, 1], squares: [10], square: 0.05}\n"),
               "t.yaml");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("t.yaml:16:"));
    EXPECT_THAT(e.what(), HasSubstr("squares"));
  }
}

}  // namespace
}  // namespace coopmap::sim
