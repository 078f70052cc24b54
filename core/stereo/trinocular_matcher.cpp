#include "core/stereo/trinocular_matcher.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

namespace coopmap {

namespace {
constexpr uint16_t kOutOfImageCost = 255;  // per pair, when no partner sees the pixel
constexpr uint16_t kOutOfImage = 0xFFFF;   // marker in per-pair differences

std::string fieldError(const std::string& field, const std::string& expected, double got) {
  return "stereo config: field '" + field + "': expected " + expected + ", got " +
         std::to_string(got);
}
}  // namespace

void StereoConfig::validate() const {
  if (num_disparities < 4 || num_disparities > 256)
    throw std::invalid_argument(fieldError("num_disparities", "4..256", num_disparities));
  if (window < 3 || window > 31 || window % 2 == 0)
    throw std::invalid_argument(fieldError("window", "an odd number in 3..31", window));
  if (!(min_texture >= 0.0))
    throw std::invalid_argument(fieldError("min_texture", "a number >= 0", min_texture));
  if (!(uniqueness >= 0.0 && uniqueness < 1.0))
    throw std::invalid_argument(fieldError("uniqueness", "a number in [0, 1)", uniqueness));
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
  for (int p = 0; p < 2; ++p) {
    PairShift& pair = pairs_[p];
    pair.enabled = enabled[p] && offsets[p].norm() > 0.0;
    // A point at disparity d (reference baseline) appears in the partner shifted by
    // -(fx tx, fy ty) / (fx b) * d pixels.
    const double su = -offsets[p].x() / b;
    const double sv = -(k.fy / k.fx) * offsets[p].y() / b;
    for (int d = 0; d < config_.num_disparities; ++d) {
      pair.du.push_back(static_cast<int>(std::lround(su * d)));
      pair.dv.push_back(static_cast<int>(std::lround(sv * d)));
    }
  }
  const size_t n = static_cast<size_t>(width_) * height_;
  abs_diff_.assign(n, 0);
  pair_diff_[0].assign(n, 0);
  pair_diff_[1].assign(n, 0);
  column_sum_.assign(width_, 0);
  cost_.assign(n * config_.num_disparities, 0);
  texture_.assign(n, 0);
  best_cost_.assign(n, 0);
  best_d_.assign(n, 0);
}

// Per-pixel absolute differences against one partner for disparity d; kOutOfImage marks
// pixels whose partner pixel is outside the partner image.
void TrinocularMatcher::pairDifferences(const PairShift& pair, const cv::Mat& ref,
                                        const cv::Mat& partner, int d, uint16_t* out) {
  const int du = pair.du[d], dv = pair.dv[d];
  for (int y = 0; y < height_; ++y) {
    uint16_t* o = out + static_cast<size_t>(y) * width_;
    const int py = y + dv;
    if (py < 0 || py >= height_) {
      std::fill(o, o + width_, kOutOfImage);
      continue;
    }
    const uint8_t* r = ref.ptr<uint8_t>(y);
    const uint8_t* q = partner.ptr<uint8_t>(py);
    const int x0 = std::clamp(-du, 0, width_), x1 = std::clamp(width_ - du, x0, width_);
    std::fill(o, o + x0, kOutOfImage);
    for (int x = x0; x < x1; ++x)
      o[x] = static_cast<uint16_t>(std::abs(int(r[x]) - int(q[x + du])));
    std::fill(o + x1, o + width_, kOutOfImage);
  }
}

// Combines the pairs' differences into abs_diff_: the sum where both partners see the
// pixel, twice the one that does where only one does (so costs stay comparable).
void TrinocularMatcher::combinePairs(int d, const cv::Mat& ref, const cv::Mat* partners[2]) {
  const size_t n = abs_diff_.size();
  const bool h = pairs_[0].enabled, v = pairs_[1].enabled;
  if (h) pairDifferences(pairs_[0], ref, *partners[0], d, pair_diff_[0].data());
  if (v) pairDifferences(pairs_[1], ref, *partners[1], d, pair_diff_[1].data());
  const uint16_t* a = pair_diff_[0].data();
  const uint16_t* b = pair_diff_[1].data();
  if (h && v) {
    for (size_t i = 0; i < n; ++i) {
      const bool ia = a[i] != kOutOfImage, ib = b[i] != kOutOfImage;
      abs_diff_[i] = static_cast<uint16_t>(ia && ib ? a[i] + b[i]
                                           : ia     ? 2 * a[i]
                                           : ib     ? 2 * b[i]
                                                    : 2 * kOutOfImageCost);
    }
  } else {
    const uint16_t* c = h ? a : b;
    for (size_t i = 0; i < n; ++i)
      abs_diff_[i] = static_cast<uint16_t>(c[i] != kOutOfImage ? 2 * c[i] : 2 * kOutOfImageCost);
  }
}

// Window sums of abs_diff_ with running column sums; pixels whose window leaves the image
// keep cost 0 and are rejected later as border pixels.
void TrinocularMatcher::boxFilterInto(uint16_t* out) {
  const int r = config_.window / 2, w = config_.window;
  std::fill(column_sum_.begin(), column_sum_.end(), 0u);
  for (int y = 0; y < w - 1; ++y) {
    const uint16_t* a = abs_diff_.data() + static_cast<size_t>(y) * width_;
    for (int x = 0; x < width_; ++x) column_sum_[x] += a[x];
  }
  for (int y = r; y < height_ - r; ++y) {
    const uint16_t* add = abs_diff_.data() + static_cast<size_t>(y + r) * width_;
    for (int x = 0; x < width_; ++x) column_sum_[x] += add[x];
    uint16_t* o = out + static_cast<size_t>(y) * width_;
    uint32_t s = 0;
    for (int x = 0; x < w - 1; ++x) s += column_sum_[x];
    for (int x = r; x < width_ - r; ++x) {
      s += column_sum_[x + r];
      o[x] = static_cast<uint16_t>(std::min<uint32_t>(s, 0xFFFF));
      s -= column_sum_[x - r];
    }
    const uint16_t* sub = abs_diff_.data() + static_cast<size_t>(y - r) * width_;
    for (int x = 0; x < width_; ++x) column_sum_[x] -= sub[x];
  }
}

StereoStats TrinocularMatcher::compute(const cv::Mat& reference, const cv::Mat& horizontal,
                                       const cv::Mat& vertical, cv::Mat& disparity) {
  const cv::Mat* partners[2] = {&horizontal, &vertical};
  for (const cv::Mat* m : {&reference, &horizontal, &vertical}) {
    if (m->type() != CV_8UC1 || m->cols != width_ || m->rows != height_)
      throw std::invalid_argument("TrinocularMatcher: images must be CV_8UC1 " +
                                  std::to_string(width_) + "x" + std::to_string(height_));
  }
  disparity.create(height_, width_, CV_32F);
  const int nd = config_.num_disparities;
  const size_t n = static_cast<size_t>(width_) * height_;

  for (int d = 0; d < nd; ++d) {
    combinePairs(d, reference, partners);
    boxFilterInto(cost_.data() + n * d);
  }

  // Texture: window sum of half the central-difference gradient magnitude (L1).
  std::fill(abs_diff_.begin(), abs_diff_.end(), 0);
  for (int y = 1; y < height_ - 1; ++y) {
    const uint8_t* up = reference.ptr<uint8_t>(y - 1);
    const uint8_t* row = reference.ptr<uint8_t>(y);
    const uint8_t* dn = reference.ptr<uint8_t>(y + 1);
    uint16_t* o = abs_diff_.data() + static_cast<size_t>(y) * width_;
    for (int x = 1; x < width_ - 1; ++x)
      o[x] = static_cast<uint16_t>(
          (std::abs(int(row[x + 1]) - int(row[x - 1])) + std::abs(int(dn[x]) - int(up[x]))) / 2);
  }
  boxFilterInto(texture_.data());

  // Winner-take-all.
  std::fill(best_cost_.begin(), best_cost_.end(), std::numeric_limits<uint16_t>::max());
  std::fill(best_d_.begin(), best_d_.end(), 0);
  for (int d = 0; d < nd; ++d) {
    const uint16_t* c = cost_.data() + n * d;
    for (size_t i = 0; i < n; ++i) {
      const bool better = c[i] < best_cost_[i];
      best_cost_[i] = better ? c[i] : best_cost_[i];
      best_d_[i] = better ? static_cast<uint8_t>(d) : best_d_[i];
    }
  }

  StereoStats stats;
  const int r = config_.window / 2;
  const double min_texture_sum = config_.min_texture * config_.window * config_.window;
  for (int y = 0; y < height_; ++y) {
    float* out = disparity.ptr<float>(y);
    for (int x = 0; x < width_; ++x) {
      out[x] = kInvalidDisparity;
      if (y < r || y >= height_ - r || x < r || x >= width_ - r) {
        ++stats.rejected_border;
        continue;
      }
      const size_t i = static_cast<size_t>(y) * width_ + x;
      if (texture_[i] < min_texture_sum) {
        ++stats.rejected_texture;
        continue;
      }
      const int bd = best_d_[i];
      if (bd == 0 || bd == nd - 1) {
        ++stats.rejected_border;
        continue;
      }
      const uint32_t best = best_cost_[i];
      uint32_t second = std::numeric_limits<uint32_t>::max();
      for (int d = 0; d < nd; ++d)
        if (d < bd - 1 || d > bd + 1) second = std::min<uint32_t>(second, cost_[n * d + i]);
      if (static_cast<double>(second) <= best * (1.0 + config_.uniqueness)) {
        ++stats.rejected_uniqueness;
        continue;
      }
      const double cm = cost_[n * (bd - 1) + i], c0 = best, cp = cost_[n * (bd + 1) + i];
      const double denom = cm - 2.0 * c0 + cp;
      const double offset = denom > 0.0 ? 0.5 * (cm - cp) / denom : 0.0;
      out[x] = static_cast<float>(bd + std::clamp(offset, -0.5, 0.5));
      ++stats.valid;
    }
  }
  return stats;
}

}  // namespace coopmap
