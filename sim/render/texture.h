// Procedural, seeded, tileable grey textures (noise, bricks, posters, near-uniform).
#pragma once

#include <opencv2/core/mat.hpp>

#include "sim/world/world.h"

namespace coopmap::sim {

// A size x size CV_8UC1 texture that tiles seamlessly; the same spec gives the same image.
cv::Mat makeTexture(const TextureSpec& spec, int size = 256);

}  // namespace coopmap::sim
