// Multibaseline SAD stereo (Okutomi-Kanade) over an L-shaped trinocular rig: for every
// reference pixel and disparity, the window SADs against both partners are summed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "core/geometry/camera.h"
#include "core/stereo/sad_kernels.h"

namespace coopmap {

// Disparity value for pixels that failed validation.
inline constexpr float kInvalidDisparity = -1.0f;

struct StereoConfig {
  int num_disparities = 32;    // disparities 0 .. num_disparities-1, in reference-baseline px
  int window = 7;              // odd window side (px), 3..11
  double min_texture = 4.0;    // minimum mean |gradient| in the window (grey levels)
  double uniqueness = 0.10;    // best must beat the runner-up (|d - best| > 1) by this fraction
  bool use_horizontal = true;  // include the horizontal pair
  bool use_vertical = true;    // include the vertical pair
  // Consistency between the pairs: at the summed cost's winner (within one disparity) each
  // pair's cost may exceed its own best by at most this fraction. 0 means each pair's own
  // winner must lie within one disparity of the summed winner or tie with it: an error in
  // one pair (an occlusion it alone sees) fails, a pair that is only ambiguous (repeated
  // texture: equal minima) passes. Negative turns the check off.
  double pair_consistency = 0.0;
  // The centre pixel's own mean absolute difference to its partners at the winner may be
  // at most this (grey levels); catches windows that win across a depth edge. 0: off.
  int max_centre_difference = 12;
  // Shiftable windows against foreground fattening: a centred window straddling a depth
  // edge is won by the better-textured side, so background pixels up to window / 2 px
  // beside an object take the object's disparity (phantom obstacle columns beside furniture).
  // Per disparity, the cost is the lowest among the windows shifted horizontally by up to
  // this many px (all still contain the pixel), so a window that stays on the pixel's own
  // side of the edge can win; window / 2 - window_shift px of fattening remain. At most
  // window / 2. With 2: Tsukuba bad pixels 2.94 -> 2.57 %, lab 0.53 -> 0.35 %, phantom
  // radial-map columns beside furniture -23 % on the same frames, door jambs before a
  // textured room kept, at 2.6x the stereo time. What measures distance on thin edges is
  // matched on centred windows all the same: the looks at the home base and the distance
  // scale from stereo (see Mapper). 0: centred windows.
  int window_shift = 2;
  // Photometric normalisation before matching. Real cameras differ in gain and offset, and
  // raw SAD does not forgive a few grey levels of offset on weak texture.
  //  kGlobal: each partner's mean and spread are matched to the reference image's (exact for
  //           a per-camera gain and offset; nothing changes at depth edges);
  //  kLocalMean: every image minus its own mean over a prefilter_window square, clamped to
  //           +-prefilter_cap (StereoBM's normalised response, unscaled): also absorbs
  //           vignetting, at some cost at depth edges (Tsukuba: 2.9 -> 3.5 % bad pixels).
  enum class Photometric { kNone, kGlobal, kLocalMean };
  Photometric photometric = Photometric::kGlobal;
  int prefilter_window = 9;  // odd px, kLocalMean only
  int prefilter_cap = 63;    // grey levels, kLocalMean only

  // Throws std::invalid_argument naming the field and the bad value.
  void validate() const;
};

// "none", "global", "local" <-> the enum; parsing throws std::invalid_argument naming the
// accepted names.
const char* toString(StereoConfig::Photometric p);
StereoConfig::Photometric parsePhotometric(const std::string& name);

struct StereoStats {
  int valid = 0;
  int rejected_texture = 0;
  int rejected_uniqueness = 0;
  int rejected_consistency = 0;
  int rejected_centre = 0;
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
    bool horizontal = true;      // the partner is displaced along x (else along y)
    double step = -1.0;          // partner image shift (px) per unit of disparity, signed
    bool unit = true;            // |step| == 1: samples are contiguous in a prepared image
    cv::Mat prepared;            // unit pairs: rows (or transposed columns) laid out along d
    std::vector<uint8_t> table;  // other ratios: this row's samples [x][d]
    std::vector<int> valid;      // other ratios: this row's leading in-image disparities
  };
  void preparePair(Pair& pair, const cv::Mat& partner);
  sad::PairRow pairRow(Pair& pair, const cv::Mat& partner, int y);
  void computeTexture(const cv::Mat& reference);
  void prefilter(const cv::Mat& in, cv::Mat& out);
  void matchGlobal(const cv::Mat& reference, const cv::Mat& partner, cv::Mat& out) const;
  void chooseShifted(bool both, uint32_t uniqueness);
  StereoStats match(const cv::Mat& reference, const cv::Mat& horizontal, const cv::Mat& vertical,
                    cv::Mat& disparity);
  // Whether reference pixel (x, y) (its row given) matches its partner pixels at integer
  // disparity d: mean absolute difference at most `max` (pairs not seeing it are skipped).
  bool centreMatches(const uint8_t* ref_row, const cv::Mat* const partners[2], int x, int y, int d,
                     int max) const {
    int sum = 0, n = 0;
    for (int p = 0; p < 2; ++p) {
      const Pair& pair = pairs_[p];
      if (!pair.enabled) continue;
      const int shift = pair.unit ? (pair.step < 0 ? -d : d)
                                  : static_cast<int>(pair.step * d + (pair.step < 0 ? -0.5 : 0.5));
      const int px = pair.horizontal ? x + shift : x, py = pair.horizontal ? y : y + shift;
      if (px < 0 || py < 0 || px >= width_ || py >= height_) continue;
      const int diff = ref_row[x] - partners[p]->ptr<uint8_t>(py)[px];
      sum += diff < 0 ? -diff : diff;
      ++n;
    }
    return sum <= max * n;
  }

  TrinocularRig rig_;
  StereoConfig config_;
  double focal_baseline_ = 0.0;
  Pair pairs_[2];
  int width_ = 0, height_ = 0;
  std::vector<uint8_t> ring_[2];      // differences of the last window + 1 rows [row][x][d]
  std::vector<uint16_t> colsum_[2];   // vertical window sums per pair [x][d]
  std::vector<uint16_t> scratch_;     // sliding sums of one pixel per pair, and their sum
  std::vector<sad::Choice> choices_;  // per pixel of the output row
  std::vector<uint8_t> skip_;         // per pixel of the output row: too little texture
  std::vector<uint16_t> texture_;     // window sums of |gradient| [y][x]
  cv::Mat filtered_[3], mean_;        // prefiltered reference, horizontal, vertical
  std::vector<int32_t> tex_col_;      // running column sums for the texture measure
  std::vector<uint16_t> box_[2];      // window_shift: window sums of the output row [x][d]
  std::vector<uint16_t> shifted_[2];  // window_shift: costs of each pixel's best windows [x][d]
  std::vector<uint32_t> keys_;        // window_shift: summed and pair-a costs packed [x][d]
};

}  // namespace coopmap
