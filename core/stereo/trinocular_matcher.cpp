#include "core/stereo/trinocular_matcher.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace coopmap {

namespace {
std::string fieldError(const std::string& field, const std::string& expected, double got) {
  return "stereo config: field '" + field + "': expected " + expected + ", got " +
         std::to_string(got);
}

// Adds (sign +1) or removes (-1) one row's half L1 central-difference gradient to the
// texture measure's column sums.
void accumulateGradient(const uint8_t* __restrict up, const uint8_t* __restrict row,
                        const uint8_t* __restrict dn, int width, int sign,
                        int32_t* __restrict col) {
  for (int x = 1; x < width - 1; ++x)
    col[x] += sign * ((std::abs(row[x + 1] - row[x - 1]) + std::abs(dn[x] - up[x])) >> 1);
}
}  // namespace

const char* toString(StereoConfig::Photometric p) {
  switch (p) {
    case StereoConfig::Photometric::kNone:
      return "none";
    case StereoConfig::Photometric::kGlobal:
      return "global";
    case StereoConfig::Photometric::kLocalMean:
      return "local";
  }
  return "?";
}

StereoConfig::Photometric parsePhotometric(const std::string& name) {
  for (auto p : {StereoConfig::Photometric::kNone, StereoConfig::Photometric::kGlobal,
                 StereoConfig::Photometric::kLocalMean})
    if (name == toString(p)) return p;
  throw std::invalid_argument(
      "stereo config: field 'photometric': expected none, global or "
      "local, got '" +
      name + "'");
}

void StereoConfig::validate() const {
  if (num_disparities < 4 || num_disparities > 256)
    throw std::invalid_argument(fieldError("num_disparities", "4..256", num_disparities));
  if (window < 3 || window > 11 || window % 2 == 0)
    throw std::invalid_argument(fieldError("window", "an odd number in 3..11", window));
  if (!(min_texture >= 0.0))
    throw std::invalid_argument(fieldError("min_texture", "a number >= 0", min_texture));
  if (!(uniqueness >= 0.0 && uniqueness < 1.0))
    throw std::invalid_argument(fieldError("uniqueness", "a number in [0, 1)", uniqueness));
  if (prefilter_window < 3 || prefilter_window > 31 || prefilter_window % 2 == 0)
    throw std::invalid_argument(
        fieldError("prefilter_window", "an odd number in 3..31", prefilter_window));
  if (window_shift < 0 || window_shift > window / 2)
    throw std::invalid_argument(fieldError(
        "window_shift", "an integer in 0..window / 2 (" + std::to_string(window / 2) + ")",
        window_shift));
  if (prefilter_cap < 1 || prefilter_cap > 127)
    throw std::invalid_argument(fieldError("prefilter_cap", "1..127", prefilter_cap));
  if (!use_horizontal && !use_vertical)
    throw std::invalid_argument(
        "stereo config: fields 'use_horizontal' and 'use_vertical': expected at least one "
        "pair enabled, got none");
}

TrinocularMatcher::TrinocularMatcher(const TrinocularRig& rig, const StereoConfig& config)
    : rig_(rig), config_(config) {
  config_.validate();
  const CameraIntrinsics& k = rig.intrinsics;
  const double b = rig.referenceBaseline();
  if (!(b > 0.0)) throw std::invalid_argument("stereo rig: horizontal_offset must be non-zero");
  focal_baseline_ = k.fx * b;
  width_ = k.width;
  height_ = k.height;
  const Eigen::Vector3d offsets[2] = {rig.horizontal_offset, rig.vertical_offset};
  const bool enabled[2] = {config_.use_horizontal, config_.use_vertical};
  const char* names[2] = {"horizontal_offset", "vertical_offset"};
  for (int p = 0; p < 2; ++p) {
    Pair& pair = pairs_[p];
    const Eigen::Vector3d& t = offsets[p];
    pair.enabled = enabled[p] && t.norm() > 0.0;
    if (!pair.enabled) continue;
    // A rectified L-rig: each partner is displaced along one image axis only.
    const bool along_x = std::abs(t.y()) < 1e-9 && std::abs(t.z()) < 1e-9;
    const bool along_y = std::abs(t.x()) < 1e-9 && std::abs(t.z()) < 1e-9;
    if (!along_x && !along_y)
      throw std::invalid_argument(std::string("stereo rig: ") + names[p] +
                                  ": expected a rectified partner displaced along x or y only");
    pair.horizontal = along_x;
    // A point at disparity d (reference baseline) appears in the partner shifted by
    // -(fx tx, fy ty) / (fx b) * d pixels.
    pair.step = along_x ? -t.x() / b : -(k.fy / k.fx) * t.y() / b;
    pair.unit = std::abs(std::abs(pair.step) - 1.0) < 1e-9;
    pair.valid.assign(width_, 0);
    if (!pair.unit) pair.table.assign(static_cast<size_t>(width_) * config_.num_disparities, 0);
  }
  const size_t row = static_cast<size_t>(width_) * config_.num_disparities;
  const int used = (pairs_[0].enabled ? 1 : 0) + (pairs_[1].enabled ? 1 : 0);
  for (int p = 0; p < used; ++p) {
    ring_[p].assign(row * (config_.window + 1), 0);
    colsum_[p].assign(row, 0);
    if (config_.window_shift > 0) {
      box_[p].assign(row, 0);
      shifted_[p].assign(row, 0);
    }
  }
  if (config_.window_shift > 0) keys_.assign(row + config_.num_disparities, 0);
  scratch_.assign(3 * static_cast<size_t>(config_.num_disparities), 0);
  choices_.assign(width_, sad::Choice{});
  skip_.assign(width_, 0);
  texture_.assign(static_cast<size_t>(width_) * height_, 0);
  tex_col_.assign(width_, 0);
}

// Lays a unit-ratio partner out so that the samples of disparities 0, 1, 2, ... of a
// reference pixel are contiguous: rows (reversed when the shift is negative) for a
// horizontal partner, columns (transposed) for a vertical one; padded by num_disparities.
void TrinocularMatcher::preparePair(Pair& pair, const cv::Mat& partner) {
  if (!pair.unit) return;
  const int nd = config_.num_disparities;
  const int rows = pair.horizontal ? height_ : width_, cols = pair.horizontal ? width_ : height_;
  pair.prepared.create(rows, cols + nd, CV_8UC1);
  cv::Mat body = pair.prepared(cv::Rect(0, 0, cols, rows));  // never writes into `partner`
  if (pair.horizontal) {
    if (pair.step < 0)
      cv::flip(partner, body, 1);
    else
      partner.copyTo(body);
  } else {
    cv::transpose(partner, body);
    if (pair.step < 0) cv::flip(body, body, 1);
  }
  pair.prepared(cv::Rect(cols, 0, nd, rows)).setTo(0);
}

// Where the samples of every pixel of reference row y lie.
sad::PairRow TrinocularMatcher::pairRow(Pair& pair, const cv::Mat& partner, int y) {
  sad::PairRow row;
  if (!pair.enabled) return row;
  const int nd = config_.num_disparities;
  const int n = pair.horizontal ? width_ : height_;  // length of the partner's epipolar line
  if (pair.unit) {
    // Samples are contiguous in the prepared image; past the line's end lies padding.
    if (pair.horizontal) {
      row.base = pair.prepared.ptr<uint8_t>(y) + (pair.step < 0 ? n - 1 : 0);
      row.stride = pair.step < 0 ? -1 : 1;
      row.valid0 = pair.step < 0 ? 1 : n;  // valid = valid0 + valid_per_x * x
      row.valid_per_x = pair.step < 0 ? 1 : -1;
    } else {
      const int start = pair.step < 0 ? n - 1 - y : y;
      row.base = pair.prepared.ptr<uint8_t>(0) + start;
      row.stride = static_cast<ptrdiff_t>(pair.prepared.step[0]);
      row.valid0 = n - start;
      row.valid_per_x = 0;
    }
    return row;
  }
  // Other baseline ratios: linear interpolation along the epipolar line into a table.
  for (int x = 0; x < width_; ++x) {
    const int along = pair.horizontal ? x : y;
    uint8_t* t = pair.table.data() + static_cast<size_t>(x) * nd;
    int valid = 0;
    for (int d = 0; d < nd; ++d) {
      const double pos = along + pair.step * d;
      if (pos < 0.0 || pos > n - 1) break;
      const int i0 = static_cast<int>(pos), i1 = std::min(i0 + 1, n - 1);
      const double f = pos - i0;
      const double v0 = pair.horizontal ? partner.at<uint8_t>(y, i0) : partner.at<uint8_t>(i0, x);
      const double v1 = pair.horizontal ? partner.at<uint8_t>(y, i1) : partner.at<uint8_t>(i1, x);
      t[d] = static_cast<uint8_t>(std::lround(v0 + f * (v1 - v0)));
      valid = d + 1;
    }
    pair.valid[x] = valid;
  }
  row.base = pair.table.data();
  row.stride = nd;
  row.valid_table = pair.valid.data();
  return row;
}

// Window sums of half the central-difference gradient (L1) of the reference image.
void TrinocularMatcher::computeTexture(const cv::Mat& reference) {
  const int r = config_.window / 2, w = config_.window;
  std::fill(tex_col_.begin(), tex_col_.end(), 0u);
  auto gradientRow = [&](int y, int sign) {
    if (y <= 0 || y >= height_ - 1) return;
    accumulateGradient(reference.ptr<uint8_t>(y - 1), reference.ptr<uint8_t>(y),
                       reference.ptr<uint8_t>(y + 1), width_, sign, tex_col_.data());
  };
  for (int y = 0; y < height_; ++y) {
    gradientRow(y, +1);
    if (y >= w) gradientRow(y - w, -1);
    if (y < w - 1) continue;
    const int yc = y - r;
    uint16_t* out = texture_.data() + static_cast<size_t>(yc) * width_;
    int32_t s = 0;
    for (int x = 0; x < w - 1; ++x) s += tex_col_[x];
    for (int x = r; x < width_ - r; ++x) {
      s += tex_col_[x + r];
      out[x] = static_cast<uint16_t>(std::min<int32_t>(s, 0xFFFF));
      s -= tex_col_[x - r];
    }
  }
}

StereoStats TrinocularMatcher::compute(const cv::Mat& reference, const cv::Mat& horizontal,
                                       const cv::Mat& vertical, cv::Mat& disparity) {
  for (const cv::Mat* m : {&reference, &horizontal, &vertical}) {
    if (m->type() != CV_8UC1 || m->cols != width_ || m->rows != height_)
      throw std::invalid_argument("TrinocularMatcher: images must be CV_8UC1 " +
                                  std::to_string(width_) + "x" + std::to_string(height_));
  }
  // The texture measure is taken on the raw reference (gradients ignore offsets anyway).
  computeTexture(reference);
  switch (config_.photometric) {
    case StereoConfig::Photometric::kNone:
      break;
    case StereoConfig::Photometric::kGlobal:
      matchGlobal(reference, horizontal, filtered_[1]);
      matchGlobal(reference, vertical, filtered_[2]);
      return match(reference, filtered_[1], filtered_[2], disparity);
    case StereoConfig::Photometric::kLocalMean: {
      const cv::Mat* raw[3] = {&reference, &horizontal, &vertical};
      for (int i = 0; i < 3; ++i) prefilter(*raw[i], filtered_[i]);
      return match(filtered_[0], filtered_[1], filtered_[2], disparity);
    }
  }
  return match(reference, horizontal, vertical, disparity);
}

// out = (partner - mean) * spread_ref / spread + mean_ref, rounded and saturated.
void TrinocularMatcher::matchGlobal(const cv::Mat& reference, const cv::Mat& partner,
                                    cv::Mat& out) const {
  cv::Scalar mean_ref, spread_ref, mean, spread;
  cv::meanStdDev(reference, mean_ref, spread_ref);
  cv::meanStdDev(partner, mean, spread);
  const double gain = spread[0] > 1e-6 ? spread_ref[0] / spread[0] : 1.0;
  partner.convertTo(out, CV_8U, gain, mean_ref[0] - gain * mean[0]);
}

// out = clamp(in - box mean of in, -cap, cap) + 128.
void TrinocularMatcher::prefilter(const cv::Mat& in, cv::Mat& out) {
  const int w = config_.prefilter_window, cap = config_.prefilter_cap;
  cv::boxFilter(in, mean_, CV_32F, cv::Size(w, w), cv::Point(-1, -1), true, cv::BORDER_REPLICATE);
  out.create(in.rows, in.cols, CV_8UC1);
  const float lo = static_cast<float>(-cap), hi = static_cast<float>(cap);
  for (int y = 0; y < in.rows; ++y) {
    const uint8_t* a = in.ptr<uint8_t>(y);
    const float* m = mean_.ptr<float>(y);
    uint8_t* o = out.ptr<uint8_t>(y);
    for (int x = 0; x < in.cols; ++x)
      o[x] = static_cast<uint8_t>(std::lround(std::clamp(a[x] - m[x], lo, hi) + 128.0f));
  }
}

// Chooses every pixel of the current output row on shiftable windows (Bobick and Intille;
// Fusiello et al.'s SMW, here along x only): per disparity, the lowest summed cost among the
// windows centred up to window_shift px left or right of the pixel, each pair taking its
// cost from that same window. Then the usual choice (chooseRow with a one-column "window"
// over those costs).
void TrinocularMatcher::chooseShifted(bool both, uint32_t uniqueness) {
  const int nd = config_.num_disparities, r = config_.window / 2, s = config_.window_shift;
  for (int p = 0; p < (both ? 2 : 1); ++p)
    sad::boxRow(colsum_[p].data(), width_, nd, config_.window, box_[p].data());
  sad::shiftWindows(box_[0].data(), both ? box_[1].data() : nullptr, width_, nd, r, s, keys_.data(),
                    shifted_[0].data(), both ? shifted_[1].data() : nullptr);
  for (int x = 0; x < r; ++x) skip_[x] = skip_[width_ - 1 - x] = 1;  // no window sums there
  sad::chooseRow(shifted_[0].data(), both ? shifted_[1].data() : nullptr, width_, nd, 1,
                 skip_.data(), uniqueness, scratch_.data(), choices_.data());
}

StereoStats TrinocularMatcher::match(const cv::Mat& reference, const cv::Mat& horizontal,
                                     const cv::Mat& vertical, cv::Mat& disparity) {
  const cv::Mat* partners[2] = {&horizontal, &vertical};
  for (int p = 0; p < 2; ++p)
    if (pairs_[p].enabled) preparePair(pairs_[p], *partners[p]);
  disparity.create(height_, width_, CV_32F);
  disparity.setTo(kInvalidDisparity);

  const int nd = config_.num_disparities, w = config_.window, r = w / 2;
  const size_t row_len = static_cast<size_t>(width_) * nd;
  const uint32_t min_texture_sum = static_cast<uint32_t>(std::ceil(config_.min_texture * w * w));
  // Uniqueness in 1/1024ths: reject when second * 1024 <= best * (1024 + u).
  const uint64_t uniq = static_cast<uint64_t>(std::lround(config_.uniqueness * 1024.0));
  for (auto& c : colsum_) std::fill(c.begin(), c.end(), 0);
  const bool both = pairs_[0].enabled && pairs_[1].enabled;
  const bool check_pairs = both && config_.pair_consistency >= 0.0;
  const uint64_t pair_tol =
      static_cast<uint64_t>(std::lround(std::max(0.0, config_.pair_consistency) * 1024.0));
  StereoStats stats;
  stats.rejected_border = 2 * r * width_ + 2 * r * (height_ - 2 * r);
  Pair& a = pairs_[0];
  Pair& b = pairs_[1];

  for (int y = 0; y < height_; ++y) {
    // w + 1 ring slots: row y - w, which leaves the window now, is still in its slot.
    const size_t slot = row_len * (y % (w + 1)), leaving = row_len * ((y + 1) % (w + 1));
    // With one pair, it is "a" whichever it is.
    const sad::PairRow ra = pairRow(a, horizontal, y), rb = pairRow(b, vertical, y);
    sad::differenceRow(reference.ptr<uint8_t>(y), width_, nd, ra.base ? ra : rb,
                       ra.base ? rb : sad::PairRow{}, ring_[0].data() + slot,
                       both ? ring_[1].data() + slot : nullptr);
    for (int p = 0; p < (both ? 2 : 1); ++p)
      sad::updateColumnSums(colsum_[p].data(), ring_[p].data() + slot,
                            y >= w ? ring_[p].data() + leaving : nullptr, row_len);
    if (y < w - 1) continue;

    // Output row yc: slide the window along x and choose per pixel.
    const int yc = y - r;
    float* out = disparity.ptr<float>(yc);
    const uint16_t* tex = texture_.data() + static_cast<size_t>(yc) * width_;
    const uint8_t* ref_row = reference.ptr<uint8_t>(yc);
    for (int x = 0; x < width_; ++x) skip_[x] = tex[x] < min_texture_sum;
    if (config_.window_shift > 0) {
      chooseShifted(both, static_cast<uint32_t>(uniq));
    } else {
      sad::chooseRow(colsum_[0].data(), both ? colsum_[1].data() : nullptr, width_, nd, w,
                     skip_.data(), static_cast<uint32_t>(uniq), scratch_.data(), choices_.data());
    }
    for (int x = r; x < width_ - r; ++x) {
      const sad::Choice& ch = choices_[x];
      if (skip_[x]) {
        ++stats.rejected_texture;
        continue;
      }
      if (ch.d == 0 || ch.d == nd - 1) {
        ++stats.rejected_border;  // at the end of the searched range
        continue;
      }
      if (uint64_t(ch.second) * 1024 <= uint64_t(ch.best) * (1024 + uniq)) {
        ++stats.rejected_uniqueness;
        continue;
      }
      // Each pair must find the winner (within a disparity) about as good as its own best:
      // an occlusion or mismatch in one pair shows as a clearly better minimum elsewhere,
      // while a pair that is merely ambiguous (repeated texture) agrees.
      if (check_pairs && (uint64_t(ch.near_a) * 1024 > uint64_t(ch.min_a) * (1024 + pair_tol) ||
                          uint64_t(ch.near_b) * 1024 > uint64_t(ch.min_b) * (1024 + pair_tol))) {
        ++stats.rejected_consistency;
        continue;
      }
      // The centre pixel itself must match: near depth edges a window can win with its
      // other pixels while the centre belongs to the surface behind ("fattening").
      if (config_.max_centre_difference > 0 &&
          !centreMatches(ref_row, partners, x, yc, ch.d, config_.max_centre_difference)) {
        ++stats.rejected_centre;
        continue;
      }
      // Sub-pixel: equiangular (V) fit, which SAD costs follow; a parabola pulls towards
      // whole pixels ("pixel locking") and makes flat walls wavy at long range.
      const double rise = double(std::max(ch.minus, ch.plus)) - double(ch.best);
      const double offset = rise > 0.0 ? 0.5 * (double(ch.minus) - double(ch.plus)) / rise : 0.0;
      out[x] = static_cast<float>(ch.d + std::clamp(offset, -0.5, 0.5));
      ++stats.valid;
    }
  }
  return stats;
}

}  // namespace coopmap
