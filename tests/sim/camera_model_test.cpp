#include "sim/sensors/camera_model.h"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

namespace coopmap::sim {
namespace {

TEST(CameraModelTest, NoiseGainAndOffsetAsConfigured) {
  CameraNoiseConfig c;
  c.pixel_sigma = 3.0;
  c.gain_spread = 0.05;
  c.offset_spread = 4.0;
  CameraModel cam(c, 11);
  cv::Mat img(120, 160, CV_8UC1, cv::Scalar(100));
  cam.apply(img);
  cv::Scalar mean, stddev;
  cv::meanStdDev(img, mean, stddev);
  EXPECT_NEAR(mean[0], 100 * cam.gain() + cam.offset(), 0.2);
  EXPECT_NEAR(stddev[0], 3.0, 0.15);  // rounding to grey levels adds about 0.3 in quadrature
  EXPECT_NE(cam.gain(), 1.0);
}

TEST(CameraModelTest, SameSeedSameImagesOtherSeedOthers) {
  CameraNoiseConfig c;
  c.pixel_sigma = 2.0;
  auto shot = [&](uint64_t seed) {
    CameraModel cam(c, seed);
    cv::Mat img(40, 40, CV_8UC1, cv::Scalar(128));
    cam.apply(img);
    cam.apply(img);  // the second frame draws new noise
    return img;
  };
  EXPECT_EQ(cv::norm(shot(5), shot(5), cv::NORM_L1), 0.0);
  EXPECT_GT(cv::norm(shot(5), shot(6), cv::NORM_L1), 0.0);
}

TEST(CameraModelTest, OffMeansUntouched) {
  CameraModel cam(CameraNoiseConfig{}, 1);
  cv::Mat img(10, 10, CV_8UC1, cv::Scalar(77));
  cam.apply(img);
  EXPECT_EQ(cv::countNonZero(img != 77), 0);
}

TEST(CameraModelTest, BadConfigNamesTheField) {
  CameraNoiseConfig c;
  c.blur_sigma = -1;
  try {
    CameraModel cam(c, 1);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'blur_sigma'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace coopmap::sim
