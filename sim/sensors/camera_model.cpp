#include "sim/sensors/camera_model.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace coopmap::sim {

void CameraNoiseConfig::validate() const {
  auto bad = [](const std::string& f, const std::string& e, double v) {
    throw std::invalid_argument("camera noise: field '" + f + "': expected " + e + ", got " +
                                std::to_string(v));
  };
  if (!(pixel_sigma >= 0.0 && pixel_sigma <= 50.0))
    bad("pixel_sigma", "[0, 50] grey levels", pixel_sigma);
  if (!(gain_spread >= 0.0 && gain_spread <= 0.5)) bad("gain_spread", "[0, 0.5]", gain_spread);
  if (!(offset_spread >= 0.0 && offset_spread <= 50.0))
    bad("offset_spread", "[0, 50] grey levels", offset_spread);
  if (!(blur_sigma >= 0.0 && blur_sigma <= 5.0)) bad("blur_sigma", "[0, 5] px", blur_sigma);
}

CameraModel::CameraModel(const CameraNoiseConfig& config, uint64_t seed)
    : config_(config), rng_(seed) {
  config_.validate();
  std::normal_distribution<double> n(0.0, 1.0);
  gain_ = 1.0 + config_.gain_spread * n(rng_);
  offset_ = config_.offset_spread * n(rng_);
  if (config_.pixel_sigma > 0.0) {
    noise_.resize(1 << 16);  // a power of two: the index wraps with a mask
    for (float& v : noise_) v = static_cast<float>(config_.pixel_sigma * n(rng_));
  }
}

void CameraModel::apply(cv::Mat& image) {
  if (!config_.enabled()) return;
  image.convertTo(work_, CV_32F, gain_, offset_);
  if (config_.blur_sigma > 0.0) cv::GaussianBlur(work_, work_, cv::Size(0, 0), config_.blur_sigma);
  if (config_.pixel_sigma > 0.0) {
    // Gaussian samples drawn once into a table; each frame reads it from a random start
    // with a random odd stride (cheap, and still seeded).
    const size_t n = noise_.size();
    size_t i = rng_() % n;
    const size_t stride = (rng_() % (n / 2)) * 2 + 1;
    for (int y = 0; y < work_.rows; ++y) {
      float* row = work_.ptr<float>(y);
      for (int x = 0; x < work_.cols; ++x, i = (i + stride) & (n - 1)) row[x] += noise_[i];
    }
  }
  work_.convertTo(image, CV_8U);  // rounds and saturates
}

}  // namespace coopmap::sim
