// Procedural, seeded, tileable grey textures (noise, bricks, posters, near-uniform).
#pragma once

#include <opencv2/core/mat.hpp>

#include "sim/world/world.h"

namespace coopmap::sim {

// A size x size CV_8UC1 texture that tiles seamlessly; the same spec gives the same image.
cv::Mat makeTexture(const TextureSpec& spec, int size = 256);

// The print of a checkerboard target, border included: CV_8UC1, `px_per_square` texels per
// square, row 0 the board's top edge (board -y), column 0 its left edge (board -x).
cv::Mat makeCheckerboardTexture(const TargetSpec& target, int px_per_square = 32);

}  // namespace coopmap::sim
