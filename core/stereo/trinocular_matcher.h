// Multibaseline SAD stereo (Okutomi-Kanade) over an L-shaped trinocular rig: for every
// reference pixel and disparity, the window SADs against both partners are summed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "core/geometry/camera.h"

namespace coopmap {

namespace detail {
// A pixel's winning disparity, its cost and its neighbours', and the runner-up's cost.
struct StereoChoice {
  int d = 0;
  uint32_t best = 0, second = 0, minus = 0, plus = 0;
};
// Where one partner's samples for the pixels of a reference row lie: pixel x's samples for
// disparities 0, 1, 2, ... start at base + x * stride; the first valid(x) lie inside the
// partner image, and num_disparities bytes are always readable.
struct PairRow {
  const uint8_t* base = nullptr;  // null: the pair is not used
  ptrdiff_t stride = 0;
  int valid0 = 0, valid_per_x = 0;  // valid(x) = valid0 + valid_per_x * x ...
  const int* valid_table = nullptr;  // ... unless a table gives it
  const uint8_t* samples(int x) const { return base ? base + stride * x : nullptr; }
  int valid(int x) const {
    return !base ? 0 : valid_table ? valid_table[x] : valid0 + valid_per_x * x;
  }
};
}  // namespace detail

// Disparity value for pixels that failed validation.
inline constexpr float kInvalidDisparity = -1.0f;

struct StereoConfig {
  int num_disparities = 32;    // disparities 0 .. num_disparities-1, in reference-baseline px
  int window = 7;              // odd window side (px), 3..11
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
// Costs are aggregated row by row with running box sums over a ring of `window` rows,
// disparities contiguous so the compiler vectorizes over d (AVX2 chosen at run time where
// the processor has it). Not thread-safe; use one per thread.
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
  // Where a partner's samples for disparities 0, 1, 2, ... of a reference pixel lie.
  struct Pair {
    bool enabled = false;
    bool horizontal = true;  // the partner is displaced along x (else along y)
    double step = -1.0;      // partner image shift (px) per unit of disparity, signed
    bool unit = true;        // |step| == 1: samples are contiguous in a prepared image
    cv::Mat prepared;        // unit pairs: rows (or transposed columns) laid out along d
    std::vector<uint8_t> table;  // other ratios: this row's samples [x][d]
    std::vector<int> valid;      // other ratios: this row's leading in-image disparities
  };
  void preparePair(Pair& pair, const cv::Mat& partner);
  detail::PairRow pairRow(Pair& pair, const cv::Mat& partner, int y);
  void computeTexture(const cv::Mat& reference);

  TrinocularRig rig_;
  StereoConfig config_;
  double focal_baseline_ = 0.0;
  Pair pairs_[2];
  int width_ = 0, height_ = 0;
  std::vector<uint16_t> ring_;     // absolute differences of the last window + 1 rows [row][x][d]
  std::vector<uint16_t> colsum_;   // vertical window sums [x][d]
  std::vector<uint16_t> cost_;     // aggregated costs of one pixel [d]
  std::vector<detail::StereoChoice> choices_;  // per pixel of the output row
  std::vector<uint16_t> texture_;  // window sums of |gradient| [y][x]
  std::vector<int32_t> tex_col_;   // running column sums for the texture measure
};

}  // namespace coopmap
