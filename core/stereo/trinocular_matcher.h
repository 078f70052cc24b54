// Multibaseline SAD stereo (Okutomi-Kanade) over an L-shaped trinocular rig: for every
// reference pixel and disparity, the window SADs against both partners are summed.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "core/geometry/camera.h"

namespace coopmap {

// Disparity value for pixels that failed validation.
inline constexpr float kInvalidDisparity = -1.0f;

struct StereoConfig {
  int num_disparities = 32;    // disparities 0 .. num_disparities-1, in reference-baseline px
  int window = 7;              // odd window side (px)
  double min_texture = 4.0;    // minimum mean |gradient| in the window (grey levels)
  double uniqueness = 0.10;    // best must beat the runner-up (|d - best| > 1) by this fraction
  bool use_horizontal = true;  // include the horizontal pair
  bool use_vertical = true;    // include the vertical pair

  // Throws std::invalid_argument naming the field and the bad value.
  void validate() const;
};

struct StereoStats {
  int valid = 0;
  int rejected_texture = 0;
  int rejected_uniqueness = 0;
  int rejected_border = 0;
};

// Reusable matcher: scratch buffers live here, so repeated frames allocate nothing.
// Not thread-safe; use one per thread.
class TrinocularMatcher {
 public:
  TrinocularMatcher(const TrinocularRig& rig, const StereoConfig& config);

  // Computes the reference-image disparity (CV_32F, px of the reference baseline) into
  // `disparity`; invalid pixels are kInvalidDisparity. Images are CV_8UC1 of rig size.
  StereoStats compute(const cv::Mat& reference, const cv::Mat& horizontal, const cv::Mat& vertical,
                      cv::Mat& disparity);

  // Depth (m, along the reference optical axis) of a disparity in reference-baseline px.
  double depthFromDisparity(double d) const { return focal_baseline_ / d; }
  double focalBaseline() const { return focal_baseline_; }
  const StereoConfig& config() const { return config_; }

 private:
  struct PairShift {
    bool enabled = false;
    std::vector<int> du, dv;  // integer image shift of the partner per disparity
  };
  void pairDifferences(const PairShift& pair, const cv::Mat& ref, const cv::Mat& partner, int d,
                       uint16_t* out);
  void combinePairs(int d, const cv::Mat& ref, const cv::Mat* partners[2]);
  void boxFilterInto(uint16_t* out);

  TrinocularRig rig_;
  StereoConfig config_;
  double focal_baseline_ = 0.0;
  PairShift pairs_[2];
  int width_ = 0, height_ = 0;
  std::vector<uint16_t> pair_diff_[2];  // per-pair absolute differences, one disparity
  std::vector<uint16_t> abs_diff_;      // per-pixel combined absolute differences
  std::vector<uint32_t> column_sum_;    // running vertical window sums
  std::vector<uint16_t> cost_;          // aggregated costs [d][y][x]
  std::vector<uint16_t> texture_;       // window sum of |gradient|
  std::vector<uint16_t> best_cost_;
  std::vector<uint8_t> best_d_;
};

}  // namespace coopmap
