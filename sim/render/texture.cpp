#include "sim/render/texture.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace coopmap::sim {

namespace {
// splitmix64: a small, fully specified generator, so textures match on every platform.
struct Rng {
  uint64_t s;
  uint64_t next() {
    uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return (next() >> 11) * (1.0 / 9007199254740992.0); }  // [0, 1)
};

// Periodic value noise with `cells` lattice cells across the tile, smooth-step interpolated.
std::vector<double> valueNoise(int size, int cells, Rng& rng) {
  cells = std::max(1, cells);
  std::vector<double> lattice(static_cast<size_t>(cells) * cells);
  for (double& v : lattice) v = rng.uniform() * 2.0 - 1.0;
  std::vector<double> out(static_cast<size_t>(size) * size);
  for (int y = 0; y < size; ++y) {
    const double fy = static_cast<double>(y) * cells / size;
    const int y0 = static_cast<int>(fy) % cells, y1 = (y0 + 1) % cells;
    double ty = fy - std::floor(fy);
    ty = ty * ty * (3 - 2 * ty);
    for (int x = 0; x < size; ++x) {
      const double fx = static_cast<double>(x) * cells / size;
      const int x0 = static_cast<int>(fx) % cells, x1 = (x0 + 1) % cells;
      double tx = fx - std::floor(fx);
      tx = tx * tx * (3 - 2 * tx);
      const double a = lattice[y0 * cells + x0], b = lattice[y0 * cells + x1];
      const double c = lattice[y1 * cells + x0], d = lattice[y1 * cells + x1];
      out[static_cast<size_t>(y) * size + x] =
          (a * (1 - tx) + b * tx) * (1 - ty) + (c * (1 - tx) + d * tx) * ty;
    }
  }
  return out;
}

// Multi-octave noise whose finest features are about `feature` m on a `tile` m texture.
std::vector<double> fractalNoise(int size, const TextureSpec& spec, Rng& rng) {
  std::vector<double> sum(static_cast<size_t>(size) * size, 0.0);
  const int finest =
      std::clamp(static_cast<int>(std::lround(spec.tile / spec.feature)), 1, size / 2);
  double amp = 1.0, norm = 0.0;
  for (int cells = finest; cells >= 1 && amp > 0.1; cells /= 2, amp *= 0.6) {
    const auto layer = valueNoise(size, cells, rng);
    for (size_t i = 0; i < sum.size(); ++i) sum[i] += amp * layer[i];
    norm += amp;
  }
  for (double& v : sum) v /= norm;
  return sum;
}
}  // namespace

cv::Mat makeTexture(const TextureSpec& spec, int size) {
  Rng rng{spec.seed};
  std::vector<double> v = fractalNoise(size, spec, rng);  // roughly in [-1, 1]
  const double px_per_m = size / spec.tile;
  switch (spec.type) {
    case TextureType::kNoise:
      for (double& x : v) x *= 1.6;
      break;
    case TextureType::kUniform:
      for (double& x : v) x *= 0.1;  // nearly featureless, like a painted wall
      break;
    case TextureType::kBricks: {
      // Bricks of ~0.25 x 0.08 m scaled to the tile, mortar lines, per-brick shade.
      const int rows = std::max(2, static_cast<int>(std::lround(spec.tile / 0.08)) & ~1);
      const int cols = std::max(1, static_cast<int>(std::lround(spec.tile / 0.25)));
      std::vector<double> shade(static_cast<size_t>(rows) * cols);
      for (double& s : shade) s = rng.uniform() * 1.2 - 0.6;
      const double mortar = std::max(1.0, 0.012 * px_per_m);
      for (int y = 0; y < size; ++y) {
        const double by = static_cast<double>(y) * rows / size;
        const int row = static_cast<int>(by);
        for (int x = 0; x < size; ++x) {
          const double bx = static_cast<double>(x) * cols / size + (row % 2 ? 0.5 : 0.0);
          const int col = static_cast<int>(bx) % cols;
          const double ex = (bx - std::floor(bx)) * size / cols, ey = (by - row) * size / rows;
          const bool in_mortar = ex < mortar || ey < mortar;
          double& p = v[static_cast<size_t>(y) * size + x];
          p = in_mortar ? -1.0 : 0.4 * p + shade[static_cast<size_t>(row) * cols + col];
        }
      }
      break;
    }
    case TextureType::kPosters: {
      for (double& x : v) x *= 0.8;
      const int posters = 6 + static_cast<int>(rng.uniform() * 6);
      for (int k = 0; k < posters; ++k) {
        const int w = static_cast<int>(size * (0.1 + 0.25 * rng.uniform()));
        const int h = static_cast<int>(size * (0.1 + 0.25 * rng.uniform()));
        const int x0 = static_cast<int>(rng.uniform() * size),
                  y0 = static_cast<int>(rng.uniform() * size);
        const double level = rng.uniform() * 2.0 - 1.0;
        const int stripes = 2 + static_cast<int>(rng.uniform() * 6);
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x) {
            const int px = (x0 + x) % size, py = (y0 + y) % size;
            const bool stripe = ((x * stripes) / std::max(1, w)) % 2 == 0;
            v[static_cast<size_t>(py) * size + px] =
                level * (stripe ? 1.0 : -0.6) + 0.3 * v[static_cast<size_t>(py) * size + px];
          }
      }
      break;
    }
  }
  cv::Mat img(size, size, CV_8UC1);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      img.at<uint8_t>(y, x) = static_cast<uint8_t>(std::clamp(
          std::lround(spec.mean + spec.contrast * v[static_cast<size_t>(y) * size + x]), 0L, 255L));
  return img;
}

cv::Mat makeCheckerboardTexture(const TargetSpec& target, int px_per_square) {
  const int border = static_cast<int>(std::lround(target.border * px_per_square));
  const int w = target.squares_x * px_per_square + 2 * border;
  const int h = target.squares_y * px_per_square + 2 * border;
  const auto white = static_cast<uint8_t>(std::clamp(std::lround(target.white), 0L, 255L));
  const auto black = static_cast<uint8_t>(std::clamp(std::lround(target.black), 0L, 255L));
  cv::Mat img(h, w, CV_8UC1, cv::Scalar(white));
  for (int y = 0; y < target.squares_y * px_per_square; ++y) {
    uint8_t* row = img.ptr<uint8_t>(border + y) + border;
    for (int x = 0; x < target.squares_x * px_per_square; ++x)
      if ((x / px_per_square + y / px_per_square) % 2 == 0) row[x] = black;
  }
  return img;
}

}  // namespace coopmap::sim
