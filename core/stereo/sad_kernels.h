// Inner loops of the trinocular matcher (internal to core/stereo). Disparities are
// contiguous ([x][d] layouts) so loops vectorize; AVX2 versions are chosen at run time
// where the processor has AVX2, with portable versions everywhere else.
#pragma once

#include <cstddef>
#include <cstdint>

namespace coopmap::sad {

// Where one partner's samples for the pixels of a reference row lie: pixel x's samples for
// disparities 0, 1, 2, ... start at base + x * stride; the first valid(x) lie inside the
// partner image, and num_disparities bytes are always readable.
struct PairRow {
  const uint8_t* base = nullptr;  // null: the pair is not used
  ptrdiff_t stride = 0;
  int valid0 = 0, valid_per_x = 0;   // valid(x) = valid0 + valid_per_x * x ...
  const int* valid_table = nullptr;  // ... unless a table gives it
  const uint8_t* samples(int x) const { return base ? base + stride * x : nullptr; }
  int valid(int x) const {
    return !base ? 0 : valid_table ? valid_table[x] : valid0 + valid_per_x * x;
  }
};

// A pixel's winner on the summed cost, its cost and its neighbours', the runner-up away
// from the winner's neighbours; and per pair (when both are used) its own best cost and
// its best cost within one disparity of the winner.
struct Choice {
  int d = 0;
  uint32_t best = 0, second = 0, minus = 0, plus = 0;
  uint32_t min_a = 0, near_a = 0, min_b = 0, near_b = 0;
};

// Absolute differences of one reference row against each partner, [x][d] in out_a and
// out_b (out_b unused when b is). Where only one partner sees a pixel at a disparity, the
// other's difference is copied from it (so the summed cost doubles the one that sees);
// where none does, both get 255.
void differenceRow(const uint8_t* ref, int width, int nd, const PairRow& a, const PairRow& b,
                   uint8_t* out_a, uint8_t* out_b);

// colsum[i] += add[i] - drop[i] over n entries (drop may be null).
void updateColumnSums(uint16_t* colsum, const uint8_t* add, const uint8_t* drop, size_t n);

// Horizontal window sums of one row of column sums ([x][d]): box[x] = colsum[x - window / 2]
// + ... + colsum[x + window / 2] for x in [window / 2, width - window / 2); others untouched.
void boxRow(const uint16_t* colsum, int width, int nd, int window, uint16_t* box);

// Shiftable windows over one row of window sums ([x][d], valid for x in [r, width - r)):
// for every pixel x in that range and disparity d, the window centred at c in
// [x - shift, x + shift] (clipped to the range) with the lowest summed cost a[c][d] +
// b[c][d]; out_a and out_b get that window's costs of each pair (b, out_b null: one pair).
// `keys` holds (width + 1) * nd entries of scratch.
void shiftWindows(const uint16_t* a, const uint16_t* b, int width, int nd, int r, int shift,
                  uint32_t* keys, uint16_t* out_a, uint16_t* out_b);

// Slides a window x window box along one output row of column sums ([x][d]) and chooses
// per pixel x in [window / 2, width - window / 2) where skip[x] is 0 (others are left as
// they were). colsum_b null: one pair only. The pairs' own minima are only filled in where
// the winner is unique (runner-up worse by more than uniqueness / 1024; else they stay 0).
// `scratch` holds 3 * nd entries.
void chooseRow(const uint16_t* colsum_a, const uint16_t* colsum_b, int width, int nd, int window,
               const uint8_t* skip, uint32_t uniqueness, uint16_t* scratch, Choice* choices);

}  // namespace coopmap::sad
