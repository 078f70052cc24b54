#include "core/stereo/sad_kernels.h"

#include <algorithm>
#include <cstdlib>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define COOPMAP_HAVE_AVX2_PATH 1
#endif

// Portable loops are compiled twice, for AVX2 and the baseline, picked at load time.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(__SANITIZE_ADDRESS__)
#define COOPMAP_SIMD_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define COOPMAP_SIMD_CLONES
#endif
#define COOPMAP_INLINE inline __attribute__((always_inline))

namespace coopmap::sad {

namespace {

constexpr uint8_t kUnseen = 255;  // difference where no partner sees the pixel

// One pixel's differences; ND > 0 fixes the disparity count at compile time.
template <int ND>
COOPMAP_INLINE void differencePixel(int r, const uint8_t* __restrict a, int na,
                                    const uint8_t* __restrict b, int nb, int nd_runtime,
                                    uint8_t* __restrict oa, uint8_t* __restrict ob) {
  const int nd = ND > 0 ? ND : nd_runtime;
  if (!b) {  // one pair only
    for (int d = 0; d < nd; ++d)
      oa[d] = d < na ? static_cast<uint8_t>(std::abs(r - a[d])) : kUnseen;
    return;
  }
  if (na >= nd && nb >= nd) {  // the common case: both partners see every disparity
    for (int d = 0; d < nd; ++d) {
      oa[d] = static_cast<uint8_t>(std::abs(r - a[d]));
      ob[d] = static_cast<uint8_t>(std::abs(r - b[d]));
    }
    return;
  }
  // Near the image borders a partner runs out of samples at some disparity. Every sample
  // pointer has nd readable bytes (padding): compute all, select per lane.
  for (int d = 0; d < nd; ++d) {
    const bool wa = d < na, wb = d < nb;
    const uint8_t da = static_cast<uint8_t>(std::abs(r - a[d]));
    const uint8_t db = static_cast<uint8_t>(std::abs(r - b[d]));
    oa[d] = wa ? da : wb ? db : kUnseen;
    ob[d] = wb ? db : wa ? da : kUnseen;
  }
}

template <int ND>
COOPMAP_INLINE void differenceRowT(const uint8_t* ref, int width, int nd_runtime, const PairRow& pa,
                                   const PairRow& pb, uint8_t* out_a, uint8_t* out_b) {
  const int nd = ND > 0 ? ND : nd_runtime;
  for (int x = 0; x < width; ++x) {
    const size_t o = static_cast<size_t>(x) * nd;
    differencePixel<ND>(ref[x], pa.samples(x), pa.valid(x), pb.samples(x), pb.valid(x), nd,
                        out_a + o, out_b ? out_b + o : nullptr);
  }
}

COOPMAP_INLINE void addRow(uint16_t* __restrict sum, const uint16_t* __restrict row, int n) {
  for (int i = 0; i < n; ++i) sum[i] = static_cast<uint16_t>(sum[i] + row[i]);
}
COOPMAP_INLINE void subtractRow(uint16_t* __restrict sum, const uint16_t* __restrict row, int n) {
  for (int i = 0; i < n; ++i) sum[i] = static_cast<uint16_t>(sum[i] - row[i]);
}

// The runner-up loses by more than uniqueness / 1024 of the best.
COOPMAP_INLINE bool unique(const Choice& ch, uint32_t uniqueness) {
  return uint64_t(ch.second) * 1024 > uint64_t(ch.best) * (1024 + uniqueness);
}

// The smallest of c[d - 1], c[d], c[d + 1].
COOPMAP_INLINE uint32_t nearBest(const uint16_t* c, int nd, int d) {
  uint32_t m = c[d];
  if (d > 0) m = std::min<uint32_t>(m, c[d - 1]);
  if (d + 1 < nd) m = std::min<uint32_t>(m, c[d + 1]);
  return m;
}

// Smallest (cost, d): the winner, lowest d on ties.
template <int ND>
COOPMAP_INLINE int argmin(const uint16_t* __restrict c, int nd_runtime) {
  const int nd = ND > 0 ? ND : nd_runtime;
  uint32_t key = 0xFFFFFFFFu;
  for (int d = 0; d < nd; ++d) key = std::min(key, (uint32_t(c[d]) << 8) | uint32_t(d));
  return static_cast<int>(key & 0xFF);
}

template <int ND>
COOPMAP_INLINE Choice choose(const uint16_t* __restrict c, int nd_runtime) {
  const int nd = ND > 0 ? ND : nd_runtime;
  const int bd = argmin<ND>(c, nd);
  uint32_t second = 0xFFFF;
  for (int d = 0; d < nd; ++d) {
    const bool away = d + 1 < bd || d > bd + 1;
    second = std::min(second, away ? uint32_t(c[d]) : 0xFFFFu);
  }
  Choice ch;
  ch.d = bd;
  ch.best = c[bd];
  ch.second = second;
  ch.minus = bd > 0 ? c[bd - 1] : 0xFFFFu;
  ch.plus = bd + 1 < nd ? c[bd + 1] : 0xFFFFu;
  return ch;
}

template <int ND>
COOPMAP_INLINE void chooseRowT(const uint16_t* colsum_a, const uint16_t* colsum_b, int width,
                               int nd_runtime, int window, const uint8_t* skip, uint32_t uniqueness,
                               uint16_t* scratch, Choice* choices) {
  const int nd = ND > 0 ? ND : nd_runtime;
  const int r = window / 2;
  uint16_t* ca = scratch;
  uint16_t* cb = scratch + nd;
  uint16_t* c = scratch + 2 * nd;
  std::fill(scratch, scratch + 3 * nd, 0);
  for (int x = 0; x < window - 1; ++x) {
    addRow(ca, colsum_a + x * nd, nd);
    if (colsum_b) addRow(cb, colsum_b + x * nd, nd);
  }
  for (int x = r; x < width - r; ++x) {
    addRow(ca, colsum_a + (x + r) * nd, nd);
    if (colsum_b) {
      addRow(cb, colsum_b + (x + r) * nd, nd);
      for (int d = 0; d < nd; ++d) c[d] = static_cast<uint16_t>(ca[d] + cb[d]);
      if (!skip[x]) {
        Choice ch = choose<ND>(c, nd);
        if (unique(ch, uniqueness)) {  // the pairs' own minima only matter then
          ch.min_a = ca[argmin<ND>(ca, nd)];
          ch.min_b = cb[argmin<ND>(cb, nd)];
          ch.near_a = nearBest(ca, nd, ch.d);
          ch.near_b = nearBest(cb, nd, ch.d);
        }
        choices[x] = ch;
      }
      subtractRow(cb, colsum_b + (x - r) * nd, nd);
    } else {
      if (!skip[x]) choices[x] = choose<ND>(ca, nd);
    }
    subtractRow(ca, colsum_a + (x - r) * nd, nd);
  }
}

// The common disparity counts get unrolled instances; others the general loop.
#define COOPMAP_DISPATCH_ND(nd, call) \
  switch (nd) {                       \
    case 16:                          \
      call(16);                       \
      break;                          \
    case 32:                          \
      call(32);                       \
      break;                          \
    case 48:                          \
      call(48);                       \
      break;                          \
    case 64:                          \
      call(64);                       \
      break;                          \
    default:                          \
      call(0);                        \
      break;                          \
  }

COOPMAP_SIMD_CLONES
void differenceRowPortable(const uint8_t* ref, int width, int nd, const PairRow& a,
                           const PairRow& b, uint8_t* out_a, uint8_t* out_b){
#define COOPMAP_CALL(N) differenceRowT<N>(ref, width, nd, a, b, out_a, out_b)
    COOPMAP_DISPATCH_ND(nd, COOPMAP_CALL)
#undef COOPMAP_CALL
}

COOPMAP_SIMD_CLONES
    void chooseRowPortable(const uint16_t* colsum_a, const uint16_t* colsum_b, int width, int nd,
                           int window, const uint8_t* skip, uint32_t uniqueness, uint16_t* scratch,
                           Choice* choices) {
#define COOPMAP_CALL(N) \
  chooseRowT<N>(colsum_a, colsum_b, width, nd, window, skip, uniqueness, scratch, choices)
  COOPMAP_DISPATCH_ND(nd, COOPMAP_CALL)
#undef COOPMAP_CALL
}

#ifdef COOPMAP_HAVE_AVX2_PATH
bool haveAvx2() {
  static const bool avx2 = __builtin_cpu_supports("avx2");
  return avx2;
}

// differenceRowT with the common case in AVX2, 32 disparities at a time.
template <int ND>
__attribute__((target("avx2"))) void differenceRowAvx2(const uint8_t* ref, int width,
                                                       const PairRow& pa, const PairRow& pb,
                                                       uint8_t* out_a, uint8_t* out_b) {
  for (int x = 0; x < width; ++x) {
    const uint8_t* a = pa.samples(x);
    const uint8_t* b = pb.samples(x);
    const int na = pa.valid(x), nb = pb.valid(x);
    uint8_t* oa = out_a + static_cast<size_t>(x) * ND;
    uint8_t* ob = out_b + static_cast<size_t>(x) * ND;
    const __m256i r = _mm256_set1_epi8(static_cast<char>(ref[x]));
    if (na >= ND && nb >= ND) {  // the common case
      int d = 0;
      for (; d + 32 <= ND; d += 32) {
        const __m256i va = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(a + d));
        const __m256i vb = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(b + d));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(oa + d),
                            _mm256_sub_epi8(_mm256_max_epu8(r, va), _mm256_min_epu8(r, va)));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(ob + d),
                            _mm256_sub_epi8(_mm256_max_epu8(r, vb), _mm256_min_epu8(r, vb)));
      }
      if (d < ND) {  // a last 16
        const __m128i r16 = _mm256_castsi256_si128(r);
        const __m128i va = _mm_loadu_si128(reinterpret_cast<const __m128i*>(a + d));
        const __m128i vb = _mm_loadu_si128(reinterpret_cast<const __m128i*>(b + d));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(oa + d),
                         _mm_sub_epi8(_mm_max_epu8(r16, va), _mm_min_epu8(r16, va)));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(ob + d),
                         _mm_sub_epi8(_mm_max_epu8(r16, vb), _mm_min_epu8(r16, vb)));
      }
      continue;
    }
    // Near the borders: the same rule as differencePixel, lane by lane with blends.
    const __m256i iota =
        _mm256_setr_epi8(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20,
                         21, 22, 23, 24, 25, 26, 27, 28, 29, 30, 31);
    const __m256i unseen = _mm256_set1_epi8(static_cast<char>(kUnseen));
    int d = 0;
    for (; d + 32 <= ND; d += 32) {
      const __m256i idx = _mm256_add_epi8(iota, _mm256_set1_epi8(static_cast<char>(d)));
      const __m256i wa =
          _mm256_cmpgt_epi8(_mm256_set1_epi8(static_cast<char>(std::min(na, ND))), idx);
      const __m256i wb =
          _mm256_cmpgt_epi8(_mm256_set1_epi8(static_cast<char>(std::min(nb, ND))), idx);
      const __m256i va = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(a + d));
      const __m256i vb = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(b + d));
      const __m256i da = _mm256_sub_epi8(_mm256_max_epu8(r, va), _mm256_min_epu8(r, va));
      const __m256i db = _mm256_sub_epi8(_mm256_max_epu8(r, vb), _mm256_min_epu8(r, vb));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(oa + d),
                          _mm256_blendv_epi8(_mm256_blendv_epi8(unseen, db, wb), da, wa));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(ob + d),
                          _mm256_blendv_epi8(_mm256_blendv_epi8(unseen, da, wa), db, wb));
    }
    if (d < ND) {  // a last 16
      const __m128i r16 = _mm256_castsi256_si128(r), u16 = _mm256_castsi256_si128(unseen);
      const __m128i idx =
          _mm_add_epi8(_mm256_castsi256_si128(iota), _mm_set1_epi8(static_cast<char>(d)));
      const __m128i wa = _mm_cmpgt_epi8(_mm_set1_epi8(static_cast<char>(std::min(na, ND))), idx);
      const __m128i wb = _mm_cmpgt_epi8(_mm_set1_epi8(static_cast<char>(std::min(nb, ND))), idx);
      const __m128i va = _mm_loadu_si128(reinterpret_cast<const __m128i*>(a + d));
      const __m128i vb = _mm_loadu_si128(reinterpret_cast<const __m128i*>(b + d));
      const __m128i da = _mm_sub_epi8(_mm_max_epu8(r16, va), _mm_min_epu8(r16, va));
      const __m128i db = _mm_sub_epi8(_mm_max_epu8(r16, vb), _mm_min_epu8(r16, vb));
      _mm_storeu_si128(reinterpret_cast<__m128i*>(oa + d),
                       _mm_blendv_epi8(_mm_blendv_epi8(u16, db, wb), da, wa));
      _mm_storeu_si128(reinterpret_cast<__m128i*>(ob + d),
                       _mm_blendv_epi8(_mm_blendv_epi8(u16, da, wa), db, wb));
    }
  }
}

__attribute__((target("avx2"))) inline uint32_t horizontalMin(__m256i v) {
  const __m128i m = _mm_min_epu16(_mm256_castsi256_si128(v), _mm256_extracti128_si256(v, 1));
  return static_cast<uint32_t>(_mm_cvtsi128_si32(_mm_minpos_epu16(m)) & 0xFFFF);
}

// First d with c[d] == value.
__attribute__((target("avx2"))) inline int findFirst(const uint16_t* c, int nd, uint32_t value) {
  const __m256i v = _mm256_set1_epi16(static_cast<short>(value));
  for (int d = 0; d < nd; d += 16) {
    const __m256i x = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(c + d));
    const unsigned mask = static_cast<unsigned>(_mm256_movemask_epi8(_mm256_cmpeq_epi16(x, v)));
    if (mask) return d + __builtin_ctz(mask) / 2;
  }
  return 0;
}

template <int ND>
__attribute__((target("avx2"))) inline uint32_t minAvx2(const uint16_t* c) {
  __m256i m = _mm256_set1_epi16(-1);
  for (int d = 0; d < ND; d += 16)
    m = _mm256_min_epu16(m, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(c + d)));
  return horizontalMin(m);
}

template <int ND>
__attribute__((target("avx2"))) inline int argminAvx2(const uint16_t* c) {
  return findFirst(c, ND, minAvx2<ND>(c));
}

template <int ND>
__attribute__((target("avx2"))) inline Choice chooseAvx2(const uint16_t* c) {
  const int bd = argminAvx2<ND>(c);
  // Runner-up: lanes within one of the winner are masked to 0xFFFF.
  const __m256i iota = _mm256_setr_epi16(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const __m256i lo = _mm256_set1_epi16(static_cast<short>(bd - 2));
  const __m256i hi = _mm256_set1_epi16(static_cast<short>(bd + 1));
  __m256i sec = _mm256_set1_epi16(-1);
  for (int d = 0; d < ND; d += 16) {
    const __m256i idx = _mm256_add_epi16(iota, _mm256_set1_epi16(static_cast<short>(d)));
    const __m256i near =
        _mm256_andnot_si256(_mm256_cmpgt_epi16(idx, hi), _mm256_cmpgt_epi16(idx, lo));
    const __m256i v = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(c + d));
    sec = _mm256_min_epu16(sec, _mm256_or_si256(v, near));
  }
  Choice ch;
  ch.d = bd;
  ch.best = c[bd];
  ch.second = horizontalMin(sec);
  ch.minus = bd > 0 ? c[bd - 1] : 0xFFFFu;
  ch.plus = bd + 1 < ND ? c[bd + 1] : 0xFFFFu;
  return ch;
}

__attribute__((target("avx2"))) inline __m256i load(const uint16_t* p) {
  return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
}

// chooseRowT in AVX2 with the sliding sums held in registers (ND / 16 vectors per pair).
template <int ND>
__attribute__((target("avx2"))) void chooseRowAvx2(const uint16_t* colsum_a,
                                                   const uint16_t* colsum_b, int width, int window,
                                                   const uint8_t* skip, uint32_t uniqueness,
                                                   uint16_t*, Choice* choices) {
  constexpr int kV = ND / 16;
  const int r = window / 2;
  __m256i ca[kV], cb[kV];
  for (int k = 0; k < kV; ++k) ca[k] = cb[k] = _mm256_setzero_si256();
  const bool two = colsum_b != nullptr;
  for (int x = 0; x < window - 1; ++x)
    for (int k = 0; k < kV; ++k) {
      ca[k] = _mm256_add_epi16(ca[k], load(colsum_a + x * ND + 16 * k));
      if (two) cb[k] = _mm256_add_epi16(cb[k], load(colsum_b + x * ND + 16 * k));
    }
  alignas(32) uint16_t c[ND], a[ND], b[ND];
  for (int x = r; x < width - r; ++x) {
    for (int k = 0; k < kV; ++k) {
      ca[k] = _mm256_add_epi16(ca[k], load(colsum_a + (x + r) * ND + 16 * k));
      if (two) cb[k] = _mm256_add_epi16(cb[k], load(colsum_b + (x + r) * ND + 16 * k));
    }
    if (!skip[x]) {
      for (int k = 0; k < kV; ++k) {
        const __m256i sum = two ? _mm256_add_epi16(ca[k], cb[k]) : ca[k];
        _mm256_store_si256(reinterpret_cast<__m256i*>(c + 16 * k), sum);
      }
      Choice ch = chooseAvx2<ND>(c);
      if (two && unique(ch, uniqueness)) {  // the pairs' own minima only matter then
        __m256i ma = ca[0], mb = cb[0];
        for (int k = 0; k < kV; ++k) {
          ma = _mm256_min_epu16(ma, ca[k]);
          mb = _mm256_min_epu16(mb, cb[k]);
          _mm256_store_si256(reinterpret_cast<__m256i*>(a + 16 * k), ca[k]);
          _mm256_store_si256(reinterpret_cast<__m256i*>(b + 16 * k), cb[k]);
        }
        ch.min_a = horizontalMin(ma);
        ch.min_b = horizontalMin(mb);
        ch.near_a = nearBest(a, ND, ch.d);
        ch.near_b = nearBest(b, ND, ch.d);
      }
      choices[x] = ch;
    }
    for (int k = 0; k < kV; ++k) {
      ca[k] = _mm256_sub_epi16(ca[k], load(colsum_a + (x - r) * ND + 16 * k));
      if (two) cb[k] = _mm256_sub_epi16(cb[k], load(colsum_b + (x - r) * ND + 16 * k));
    }
  }
}
#endif

}  // namespace

void differenceRow(const uint8_t* ref, int width, int nd, const PairRow& a, const PairRow& b,
                   uint8_t* out_a, uint8_t* out_b) {
#ifdef COOPMAP_HAVE_AVX2_PATH
  if (haveAvx2() && a.base && b.base) {
    if (nd == 32) return differenceRowAvx2<32>(ref, width, a, b, out_a, out_b);
    if (nd == 48) return differenceRowAvx2<48>(ref, width, a, b, out_a, out_b);
    if (nd == 64) return differenceRowAvx2<64>(ref, width, a, b, out_a, out_b);
  }
#endif
  differenceRowPortable(ref, width, nd, a, b, out_a, b.base ? out_b : nullptr);
}

COOPMAP_SIMD_CLONES
void updateColumnSums(uint16_t* __restrict colsum, const uint8_t* __restrict add,
                      const uint8_t* __restrict drop, size_t n) {
  if (drop) {
    for (size_t i = 0; i < n; ++i) colsum[i] = static_cast<uint16_t>(colsum[i] + add[i] - drop[i]);
  } else {
    for (size_t i = 0; i < n; ++i) colsum[i] = static_cast<uint16_t>(colsum[i] + add[i]);
  }
}

COOPMAP_SIMD_CLONES
void boxRow(const uint16_t* __restrict colsum, int width, int nd, int window,
            uint16_t* __restrict box) {
  const int r = window / 2;
  if (width < window) return;
  uint16_t* first = box + static_cast<size_t>(r) * nd;
  std::fill(first, first + nd, 0);
  for (int x = 0; x < window; ++x) addRow(first, colsum + static_cast<size_t>(x) * nd, nd);
  for (int x = r + 1; x < width - r; ++x) {
    const uint16_t* prev = box + static_cast<size_t>(x - 1) * nd;
    const uint16_t* add = colsum + static_cast<size_t>(x + r) * nd;
    const uint16_t* drop = colsum + static_cast<size_t>(x - r - 1) * nd;
    uint16_t* out = box + static_cast<size_t>(x) * nd;
    for (int d = 0; d < nd; ++d) out[d] = static_cast<uint16_t>(prev[d] + add[d] - drop[d]);
  }
}

COOPMAP_SIMD_CLONES
void shiftWindows(const uint16_t* __restrict a, const uint16_t* __restrict b, int width, int nd,
                  int r, int shift, uint32_t* __restrict keys, uint16_t* __restrict out_a,
                  uint16_t* __restrict out_b) {
  const size_t n = static_cast<size_t>(nd);
  // key = summed cost << 16 | cost of pair a: the smallest key is the best window, and
  // carries pair a's cost (pair b's is the difference).
  for (int x = r; x < width - r; ++x) {
    const uint16_t* ca = a + x * n;
    const uint16_t* cb = b ? b + x * n : nullptr;
    uint32_t* key = keys + x * n;
    if (cb) {
      for (int d = 0; d < nd; ++d) key[d] = (uint32_t(ca[d]) + uint32_t(cb[d])) << 16 | ca[d];
    } else {
      for (int d = 0; d < nd; ++d) key[d] = uint32_t(ca[d]) << 16 | ca[d];
    }
  }
  uint32_t* best = keys + static_cast<size_t>(width) * n;  // the extra row
  for (int x = r; x < width - r; ++x) {
    const int lo = std::max(r, x - shift), hi = std::min(width - r - 1, x + shift);
    std::copy_n(keys + lo * n, n, best);
    for (int c = lo + 1; c <= hi; ++c) {
      const uint32_t* key = keys + c * n;
      for (int d = 0; d < nd; ++d) best[d] = std::min(best[d], key[d]);
    }
    uint16_t* oa = out_a + x * n;
    for (int d = 0; d < nd; ++d) oa[d] = static_cast<uint16_t>(best[d] & 0xFFFFu);
    if (out_b) {
      uint16_t* ob = out_b + x * n;
      for (int d = 0; d < nd; ++d) ob[d] = static_cast<uint16_t>((best[d] >> 16) - oa[d]);
    }
  }
}

void chooseRow(const uint16_t* colsum_a, const uint16_t* colsum_b, int width, int nd, int window,
               const uint8_t* skip, uint32_t uniqueness, uint16_t* scratch, Choice* choices) {
#ifdef COOPMAP_HAVE_AVX2_PATH
  if (haveAvx2()) {
    switch (nd) {
      case 16:
        return chooseRowAvx2<16>(colsum_a, colsum_b, width, window, skip, uniqueness, scratch,
                                 choices);
      case 32:
        return chooseRowAvx2<32>(colsum_a, colsum_b, width, window, skip, uniqueness, scratch,
                                 choices);
      case 48:
        return chooseRowAvx2<48>(colsum_a, colsum_b, width, window, skip, uniqueness, scratch,
                                 choices);
      case 64:
        return chooseRowAvx2<64>(colsum_a, colsum_b, width, window, skip, uniqueness, scratch,
                                 choices);
      default:
        break;
    }
  }
#endif
  chooseRowPortable(colsum_a, colsum_b, width, nd, window, skip, uniqueness, scratch, choices);
}

}  // namespace coopmap::sad
