#include "core/stereo/trinocular_matcher.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define COOPMAP_HAVE_AVX2_PATH 1
#endif

// Hot loops are compiled twice, for AVX2 and for the baseline, and picked at load time.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(__SANITIZE_ADDRESS__)
#define COOPMAP_SIMD_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define COOPMAP_SIMD_CLONES
#endif

namespace coopmap {

namespace {
constexpr uint16_t kNoPartnerCost = 255;  // per pair, where no partner sees the pixel

std::string fieldError(const std::string& field, const std::string& expected, double got) {
  return "stereo config: field '" + field + "': expected " + expected + ", got " +
         std::to_string(got);
}

#define COOPMAP_INLINE inline __attribute__((always_inline))

// Absolute differences of one reference pixel against both partners for every disparity:
// the sum where both partners see the pixel, twice the one that does where only one does
// (so costs stay comparable), 2 * kNoPartnerCost where none does. ND > 0 fixes the number
// of disparities at compile time so the loops unroll.
template <int ND>
COOPMAP_INLINE void differencePixel(int r, const uint8_t* __restrict a, int na,
                                    const uint8_t* __restrict b, int nb, int nd_runtime,
                                    uint16_t* __restrict o) {
  const int nd = ND > 0 ? ND : nd_runtime;
  if (a && b && na >= nd && nb >= nd) {  // the common case: both see every disparity
    for (int d = 0; d < nd; ++d)
      o[d] = static_cast<uint16_t>(std::abs(r - a[d]) + std::abs(r - b[d]));
    return;
  }
  if (!b && na >= nd) {  // one pair only
    for (int d = 0; d < nd; ++d) o[d] = static_cast<uint16_t>(2 * std::abs(r - a[d]));
    return;
  }
  // Near the image borders a partner runs out of samples at some disparity. Every sample
  // pointer has num_disparities readable bytes (padding): compute all, select per lane.
  if (a && b) {
    for (int d = 0; d < nd; ++d) {
      const int wa = d < na, wb = d < nb;
      const int sum = wa * std::abs(r - a[d]) + wb * std::abs(r - b[d]);
      o[d] = static_cast<uint16_t>((wa & wb) ? sum : (wa | wb) ? 2 * sum : 2 * kNoPartnerCost);
    }
    return;
  }
  const uint8_t* __restrict p = a ? a : b;
  const int np = a ? na : nb;
  for (int d = 0; d < nd; ++d)
    o[d] = static_cast<uint16_t>(d < np ? 2 * std::abs(r - p[d]) : 2 * kNoPartnerCost);
}

// differencePixel over a reference row; `pa` is the used pair when only one is.
template <int ND>
COOPMAP_INLINE void differenceRowT(const uint8_t* ref, int width, int nd_runtime,
                                   const detail::PairRow& pa, const detail::PairRow& pb,
                                   uint16_t* out) {
  const int nd = ND > 0 ? ND : nd_runtime;
  for (int x = 0; x < width; ++x)
    differencePixel<ND>(ref[x], pa.samples(x), pa.valid(x), pb.samples(x), pb.valid(x), nd,
                        out + static_cast<size_t>(x) * nd);
}

COOPMAP_INLINE void addRow(uint16_t* __restrict sum, const uint16_t* __restrict row, size_t n) {
  for (size_t i = 0; i < n; ++i) sum[i] = static_cast<uint16_t>(sum[i] + row[i]);
}

COOPMAP_INLINE void subtractRow(uint16_t* __restrict sum, const uint16_t* __restrict row,
                                size_t n) {
  for (size_t i = 0; i < n; ++i) sum[i] = static_cast<uint16_t>(sum[i] - row[i]);
}

using Choice = detail::StereoChoice;

template <int ND>
COOPMAP_INLINE Choice choose(const uint16_t* __restrict c, int nd_runtime) {
  const int nd = ND > 0 ? ND : nd_runtime;
  // Winner: the smallest (cost, d) packed into one word, so the search vectorizes.
  uint32_t key = 0xFFFFFFFFu;
  for (int d = 0; d < nd; ++d) key = std::min(key, (uint32_t(c[d]) << 8) | uint32_t(d));
  const int bd = static_cast<int>(key & 0xFF);
  // Runner-up: the best cost away from the winner's immediate neighbours.
  uint32_t second = 0xFFFF;
  for (int d = 0; d < nd; ++d) {
    const bool away = d + 1 < bd || d > bd + 1;
    second = std::min(second, away ? uint32_t(c[d]) : 0xFFFFu);
  }
  return {bd, key >> 8, second, bd > 0 ? c[bd - 1] : 0xFFFFu, bd + 1 < nd ? c[bd + 1] : 0xFFFFu};
}

// Moves the column sums one row down the image: adds the new row, drops the old one.
COOPMAP_SIMD_CLONES
void updateColumnSums(uint16_t* colsum, const uint16_t* add, const uint16_t* drop, size_t n) {
  if (drop) subtractRow(colsum, drop, n);
  addRow(colsum, add, n);
}

// Slides the window along one output row and chooses per pixel (x in [r, width - r)).
template <int ND>
COOPMAP_INLINE void chooseRowT(const uint16_t* colsum, int width, int nd_runtime, int window,
                               uint16_t* cost, Choice* choices) {
  const int nd = ND > 0 ? ND : nd_runtime;
  const int r = window / 2;
  std::fill(cost, cost + nd, 0);
  for (int x = 0; x < window - 1; ++x) addRow(cost, colsum + x * nd, nd);
  for (int x = r; x < width - r; ++x) {
    addRow(cost, colsum + (x + r) * nd, nd);
    choices[x] = choose<ND>(cost, nd);
    subtractRow(cost, colsum + (x - r) * nd, nd);
  }
}
#ifdef COOPMAP_HAVE_AVX2_PATH
// choose() with AVX2 for disparity counts that are multiples of 16: the same result.
__attribute__((target("avx2"))) inline Choice chooseAvx2(const uint16_t* c, int nd) {
  __m256i vmin = _mm256_set1_epi16(-1);
  for (int d = 0; d < nd; d += 16)
    vmin = _mm256_min_epu16(vmin, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(c + d)));
  const __m128i m = _mm_min_epu16(_mm256_castsi256_si128(vmin), _mm256_extracti128_si256(vmin, 1));
  const uint32_t best = static_cast<uint32_t>(_mm_cvtsi128_si32(_mm_minpos_epu16(m)) & 0xFFFF);
  const __m256i vbest = _mm256_set1_epi16(static_cast<short>(best));
  int bd = 0;
  for (int d = 0; d < nd; d += 16) {
    const __m256i v = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(c + d));
    const unsigned mask = static_cast<unsigned>(_mm256_movemask_epi8(_mm256_cmpeq_epi16(v, vbest)));
    if (mask) {
      bd = d + __builtin_ctz(mask) / 2;
      break;
    }
  }
  // Runner-up: lanes within one of the winner are masked to 0xFFFF.
  const __m256i iota = _mm256_setr_epi16(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const __m256i lo = _mm256_set1_epi16(static_cast<short>(bd - 2));
  const __m256i hi = _mm256_set1_epi16(static_cast<short>(bd + 1));
  __m256i vsec = _mm256_set1_epi16(-1);
  for (int d = 0; d < nd; d += 16) {
    const __m256i idx = _mm256_add_epi16(iota, _mm256_set1_epi16(static_cast<short>(d)));
    const __m256i near = _mm256_andnot_si256(_mm256_cmpgt_epi16(idx, hi), _mm256_cmpgt_epi16(idx, lo));
    const __m256i v = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(c + d));
    vsec = _mm256_min_epu16(vsec, _mm256_or_si256(v, near));
  }
  const __m128i s2 = _mm_min_epu16(_mm256_castsi256_si128(vsec), _mm256_extracti128_si256(vsec, 1));
  const uint32_t second = static_cast<uint32_t>(_mm_cvtsi128_si32(_mm_minpos_epu16(s2)) & 0xFFFF);
  return {bd, best, second, bd > 0 ? c[bd - 1] : 0xFFFFu, bd + 1 < nd ? c[bd + 1] : 0xFFFFu};
}

// differenceRowT with the both-partners case in AVX2 (absolute differences in 8 bits,
// 32 disparities at a time); num_disparities a multiple of 32.
template <int ND>
__attribute__((target("avx2"))) void differenceRowAvx2(const uint8_t* ref, int width,
                                                       const detail::PairRow& pa,
                                                       const detail::PairRow& pb, uint16_t* out) {
  constexpr int nd = ND;
  for (int x = 0; x < width; ++x) {
    const uint8_t* a = pa.samples(x);
    const uint8_t* b = pb.samples(x);
    const int na = pa.valid(x), nb = pb.valid(x);
    uint16_t* o = out + static_cast<size_t>(x) * nd;
    if (!(a && b && na >= nd && nb >= nd)) {
      differencePixel<ND>(ref[x], a, na, b, nb, nd, o);
      continue;
    }
    const __m256i r = _mm256_set1_epi8(static_cast<char>(ref[x]));
    for (int d = 0; d < nd; d += 32) {
      const __m256i va = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(a + d));
      const __m256i vb = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(b + d));
      const __m256i da = _mm256_sub_epi8(_mm256_max_epu8(r, va), _mm256_min_epu8(r, va));
      const __m256i db = _mm256_sub_epi8(_mm256_max_epu8(r, vb), _mm256_min_epu8(r, vb));
      const __m256i lo = _mm256_add_epi16(_mm256_cvtepu8_epi16(_mm256_castsi256_si128(da)),
                                          _mm256_cvtepu8_epi16(_mm256_castsi256_si128(db)));
      const __m256i hi = _mm256_add_epi16(_mm256_cvtepu8_epi16(_mm256_extracti128_si256(da, 1)),
                                          _mm256_cvtepu8_epi16(_mm256_extracti128_si256(db, 1)));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(o + d), lo);
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(o + d + 16), hi);
    }
  }
}

template <int ND>
__attribute__((target("avx2"))) void chooseRowAvx2T(const uint16_t* colsum, int width, int window,
                                                    uint16_t* cost, Choice* choices) {
  const int r = window / 2;
  std::fill(cost, cost + ND, 0);
  for (int x = 0; x < window - 1; ++x) addRow(cost, colsum + x * ND, ND);
  for (int x = r; x < width - r; ++x) {
    addRow(cost, colsum + (x + r) * ND, ND);
    choices[x] = chooseAvx2(cost, ND);
    subtractRow(cost, colsum + (x - r) * ND, ND);
  }
}

// True when this processor runs the AVX2 path and `nd` suits it.
bool chooseRowAvx2(const uint16_t* colsum, int width, int nd, int window, uint16_t* cost,
                   Choice* choices) {
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (!avx2) return false;
  switch (nd) {
    case 16: chooseRowAvx2T<16>(colsum, width, window, cost, choices); return true;
    case 32: chooseRowAvx2T<32>(colsum, width, window, cost, choices); return true;
    case 48: chooseRowAvx2T<48>(colsum, width, window, cost, choices); return true;
    case 64: chooseRowAvx2T<64>(colsum, width, window, cost, choices); return true;
    default: return false;
  }
}
#endif

// Adds (sign +1) or removes (-1) one row's half L1 central-difference gradient to the
// texture measure's column sums.
COOPMAP_SIMD_CLONES
void accumulateGradient(const uint8_t* __restrict up, const uint8_t* __restrict row,
                        const uint8_t* __restrict dn, int width, int sign,
                        int32_t* __restrict col) {
  for (int x = 1; x < width - 1; ++x)
    col[x] += sign * ((std::abs(row[x + 1] - row[x - 1]) + std::abs(dn[x] - up[x])) >> 1);
}

// The common disparity counts get unrolled instances; others the general loop.
#define COOPMAP_DISPATCH_ND(nd, call) \
  switch (nd) {                       \
    case 16: call(16); break;         \
    case 32: call(32); break;         \
    case 48: call(48); break;         \
    case 64: call(64); break;         \
    default: call(0); break;          \
  }

COOPMAP_SIMD_CLONES
void differenceRowPortable(const uint8_t* ref, int width, int nd, const detail::PairRow& a,
                           const detail::PairRow& b, uint16_t* out) {
#define COOPMAP_CALL(N) differenceRowT<N>(ref, width, nd, a, b, out)
  COOPMAP_DISPATCH_ND(nd, COOPMAP_CALL)
#undef COOPMAP_CALL
}

COOPMAP_SIMD_CLONES
void chooseRowPortable(const uint16_t* colsum, int width, int nd, int window, uint16_t* cost,
                       Choice* choices) {
#define COOPMAP_CALL(N) chooseRowT<N>(colsum, width, nd, window, cost, choices)
  COOPMAP_DISPATCH_ND(nd, COOPMAP_CALL)
#undef COOPMAP_CALL
}
void differenceRow(const uint8_t* ref, int width, int nd, const detail::PairRow& a,
                   const detail::PairRow& b, uint16_t* out) {
#ifdef COOPMAP_HAVE_AVX2_PATH
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2 && nd == 32) return differenceRowAvx2<32>(ref, width, a, b, out);
  if (avx2 && nd == 64) return differenceRowAvx2<64>(ref, width, a, b, out);
#endif
  differenceRowPortable(ref, width, nd, a, b, out);
}

void chooseRow(const uint16_t* colsum, int width, int nd, int window, uint16_t* cost,
               Choice* choices) {
#ifdef COOPMAP_HAVE_AVX2_PATH
  if (chooseRowAvx2(colsum, width, nd, window, cost, choices)) return;
#endif
  chooseRowPortable(colsum, width, nd, window, cost, choices);
}
}  // namespace

void StereoConfig::validate() const {
  if (num_disparities < 4 || num_disparities > 256)
    throw std::invalid_argument(fieldError("num_disparities", "4..256", num_disparities));
  if (window < 3 || window > 11 || window % 2 == 0)
    throw std::invalid_argument(fieldError("window", "an odd number in 3..11", window));
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
  ring_.assign(row * (config_.window + 1), 0);
  colsum_.assign(row, 0);
  cost_.assign(config_.num_disparities, 0);
  choices_.assign(width_, Choice{});
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
    if (pair.step < 0) cv::flip(partner, body, 1);
    else partner.copyTo(body);
  } else {
    cv::transpose(partner, body);
    if (pair.step < 0) cv::flip(body, body, 1);
  }
  pair.prepared(cv::Rect(cols, 0, nd, rows)).setTo(0);
}

// Where the samples of every pixel of reference row y lie.
detail::PairRow TrinocularMatcher::pairRow(Pair& pair, const cv::Mat& partner, int y) {
  detail::PairRow row;
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
  const cv::Mat* partners[2] = {&horizontal, &vertical};
  for (int p = 0; p < 2; ++p)
    if (pairs_[p].enabled) preparePair(pairs_[p], *partners[p]);
  computeTexture(reference);
  disparity.create(height_, width_, CV_32F);
  disparity.setTo(kInvalidDisparity);

  const int nd = config_.num_disparities, w = config_.window, r = w / 2;
  const size_t row_len = static_cast<size_t>(width_) * nd;
  const uint32_t min_texture_sum =
      static_cast<uint32_t>(std::ceil(config_.min_texture * w * w));
  // Uniqueness in 1/1024ths: reject when second * 1024 <= best * (1024 + u).
  const uint64_t uniq = static_cast<uint64_t>(std::lround(config_.uniqueness * 1024.0));
  std::fill(colsum_.begin(), colsum_.end(), 0);
  StereoStats stats;
  stats.rejected_border = 2 * r * width_ + 2 * r * (height_ - 2 * r);
  Pair& a = pairs_[0];
  Pair& b = pairs_[1];

  for (int y = 0; y < height_; ++y) {
    // w + 1 ring slots: row y - w, which leaves the window now, is still in its slot.
    uint16_t* slot = ring_.data() + row_len * (y % (w + 1));
    const uint16_t* leaving = ring_.data() + row_len * ((y + 1) % (w + 1));
    const detail::PairRow ra = pairRow(a, horizontal, y), rb = pairRow(b, vertical, y);
    differenceRow(reference.ptr<uint8_t>(y), width_, nd, ra.base ? ra : rb, ra.base ? rb : ra,
                  slot);
    updateColumnSums(colsum_.data(), slot, y >= w ? leaving : nullptr, row_len);
    if (y < w - 1) continue;

    // Output row yc: slide the window along x and choose per pixel.
    const int yc = y - r;
    float* out = disparity.ptr<float>(yc);
    const uint16_t* tex = texture_.data() + static_cast<size_t>(yc) * width_;
    chooseRow(colsum_.data(), width_, nd, w, cost_.data(), choices_.data());
    for (int x = r; x < width_ - r; ++x) {
      const Choice& ch = choices_[x];
      if (tex[x] < min_texture_sum) {
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
      const double denom = double(ch.minus) - 2.0 * ch.best + double(ch.plus);
      const double offset = denom > 0.0 ? 0.5 * (double(ch.minus) - double(ch.plus)) / denom : 0.0;
      out[x] = static_cast<float>(ch.d + std::clamp(offset, -0.5, 0.5));
      ++stats.valid;
    }
  }
  return stats;
}

}  // namespace coopmap
