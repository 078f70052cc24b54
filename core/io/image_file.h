// Reading images that come from outside (map images, recorded frames, stereo test images)
// so that a damaged file is reported by coopmap, naming it, and not by the codec libraries
// (libpng and OpenCV print to stderr on their own). The file's structure is checked before
// it is decoded: a PNG's chunks and their CRCs, a PNM header against the data that follows,
// and the size the header gives against a limit, before anything that size is allocated.
#pragma once

#include <string>
#include <string_view>

#include <opencv2/core/mat.hpp>

namespace coopmap {

// Decodes `bytes` (PNG, PGM/PPM, or another format OpenCV reads) with cv::imdecode `flags`.
// Throws ConfigError "<name>: ..." for a damaged file, an image over `max_pixels`, or one
// that does not decode.
cv::Mat decodeImage(std::string_view bytes, int flags, const std::string& name, double max_pixels);

// Reads and decodes the file at `path` (decodeImage; a missing file is a ConfigError too).
cv::Mat readImage(const std::string& path, int flags, double max_pixels);

}  // namespace coopmap
