// The matcher on real images: the Tsukuba multi-view set (reference row3.col3, horizontal
// partner row3.col4, vertical partner row2.col3), scored against truedisp.row3.col3 / 16
// over every pixel with ground truth. Skips where ../shared/data is absent.
#include <cstdio>
#include <filesystem>
#include <optional>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "core/stereo/stereo_eval.h"
#include "core/stereo/trinocular_matcher.h"

namespace coopmap {
namespace {

const std::string kDir = std::string(COOPMAP_SOURCE_DIR) + "/../shared/data/tsukuba_multiview";

struct Tsukuba {
  cv::Mat ref, hor, ver, truth;
};

std::optional<Tsukuba> load() {
  if (!std::filesystem::exists(kDir + "/truedisp.row3.col3.pgm")) return std::nullopt;
  Tsukuba t;
  t.ref = cv::imread(kDir + "/scene1.row3.col3.ppm", cv::IMREAD_GRAYSCALE);
  t.hor = cv::imread(kDir + "/scene1.row3.col4.ppm", cv::IMREAD_GRAYSCALE);
  t.ver = cv::imread(kDir + "/scene1.row2.col3.ppm", cv::IMREAD_GRAYSCALE);
  cv::imread(kDir + "/truedisp.row3.col3.pgm", cv::IMREAD_UNCHANGED)
      .convertTo(t.truth, CV_32F, 1.0 / 16);
  return t;
}

DisparityScore run(const Tsukuba& t, bool vertical) {
  TrinocularRig rig;
  rig.intrinsics.width = t.ref.cols;
  rig.intrinsics.height = t.ref.rows;
  StereoConfig c;
  c.num_disparities = 16;
  c.use_vertical = vertical;
  TrinocularMatcher m(rig, c);
  cv::Mat disp;
  m.compute(t.ref, t.hor, t.ver, disp);
  return scoreDisparity(disp, t.truth);
}

TEST(TsukubaTest, TrinocularBadPixelRateStaysUnderThreePercent) {
  const auto t = load();
  if (!t) GTEST_SKIP() << "Tsukuba images not found at " << kDir << " (../shared/data is absent)";
  const DisparityScore tri = run(*t, true);
  std::printf("Tsukuba trinocular: bad %.4f mae %.3f density %.3f\n", tri.bad_pixel_rate, tri.mae,
              tri.density);
  EXPECT_EQ(tri.evaluated, 87696);  // every pixel with ground truth (the 18 px border has none)
  EXPECT_LT(tri.bad_pixel_rate, 0.030);  // measured 0.0291
  EXPECT_GT(tri.density, 0.58);          // measured 0.603
  // The pair sum with its checks beats one pair by a wide margin.
  const DisparityScore single = run(*t, false);
  EXPECT_LT(tri.bad_pixel_rate, 0.5 * single.bad_pixel_rate);
}

// The score's bias is the mean signed error of the good pixels: a sub-pixel offset shows,
// outliers (bad pixels) do not drag it.
TEST(DisparityScoreTest, BiasIsTheMeanSignedErrorOfTheGoodPixels) {
  cv::Mat truth(10, 10, CV_32F, cv::Scalar(8.0f));
  cv::Mat disparity = truth + 0.25f;
  disparity.at<float>(0, 0) = 20.0f;  // bad: off by 12 px
  disparity.at<float>(0, 1) = 0.0f;   // invalid
  truth.at<float>(0, 2) = 0.0f;       // no truth
  const DisparityScore s = scoreDisparity(disparity, truth);
  EXPECT_EQ(s.evaluated, 99);
  EXPECT_EQ(s.valid, 98);
  EXPECT_EQ(s.bad, 1);
  EXPECT_EQ(s.good, 97);
  EXPECT_NEAR(s.bias, 0.25, 1e-6);
  EXPECT_NEAR(scoreDisparity(truth - 0.5f, truth).bias, -0.5, 1e-6);
}

// A disparity 1 % too small everywhere is a range 1 % too long: the depth scale error.
TEST(DisparityScoreTest, DepthScaleErrorIsTheRelativeRangeError) {
  cv::Mat truth(10, 10, CV_32F, cv::Scalar(4.0f));
  truth.rowRange(0, 5).setTo(8.0f);
  const DisparityScore s = scoreDisparity(truth * 0.99, truth);
  EXPECT_NEAR(s.depth_scale_error, 1.0 / 0.99 - 1.0, 1e-6);
  EXPECT_NEAR(scoreDisparity(truth, truth).depth_scale_error, 0.0, 1e-12);
}

}  // namespace
}  // namespace coopmap
