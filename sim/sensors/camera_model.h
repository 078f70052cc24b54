// What a real camera adds to a rendered image: per-camera gain and offset differences,
// optional blur, and pixel noise; seeded, so a run repeats bit for bit.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace coopmap::sim {

struct CameraNoiseConfig {
  double pixel_sigma = 0.0;    // grey levels, 1-sigma Gaussian noise per pixel and frame
  double gain_spread = 0.0;    // 1-sigma relative gain difference between cameras (fixed)
  double offset_spread = 0.0;  // 1-sigma offset difference between cameras, grey levels
  double blur_sigma = 0.0;     // px, Gaussian blur (defocus); 0: none

  bool enabled() const {
    return pixel_sigma > 0 || gain_spread > 0 || offset_spread > 0 || blur_sigma > 0;
  }
  void validate() const;  // throws std::invalid_argument naming the field
};

// One camera's imperfections. The gain and offset are drawn once from the seed.
class CameraModel {
 public:
  CameraModel(const CameraNoiseConfig& config, uint64_t seed);
  // Applies gain, offset, blur and noise to an 8-bit image in place.
  void apply(cv::Mat& image);
  double gain() const { return gain_; }
  double offset() const { return offset_; }

 private:
  CameraNoiseConfig config_;
  std::mt19937_64 rng_;
  double gain_ = 1.0, offset_ = 0.0;
  cv::Mat work_;
  std::vector<float> noise_;  // Gaussian pixel noise samples
};

}  // namespace coopmap::sim
