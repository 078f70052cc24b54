#include "core/io/image_file.h"

#include <cctype>
#include <cstdint>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "core/io/binary_io.h"
#include "core/io/yaml_reader.h"

namespace coopmap {

namespace {

uint32_t bigEndian32(std::string_view b, size_t at) {
  return (uint32_t{static_cast<uint8_t>(b[at])} << 24) |
         (uint32_t{static_cast<uint8_t>(b[at + 1])} << 16) |
         (uint32_t{static_cast<uint8_t>(b[at + 2])} << 8) |
         uint32_t{static_cast<uint8_t>(b[at + 3])};
}

std::string sizeText(double w, double h) {
  std::ostringstream s;
  s.precision(15);
  s << w << " x " << h;
  return s.str();
}

// PNG: the signature, then chunks (length, type, data, CRC-32 of type and data) from IHDR to
// IEND. Returns "" or what is wrong; `w`, `h` from IHDR.
std::string pngProblem(std::string_view b, double& w, double& h) {
  size_t at = 8;
  bool first = true;
  while (true) {
    if (b.size() - at < 12)
      return "truncated: chunk at byte " + std::to_string(at) + " cut short (no IEND chunk)";
    const uint32_t length = bigEndian32(b, at);
    if (length > b.size() - at - 12)
      return "truncated: chunk at byte " + std::to_string(at) + " says " + std::to_string(length) +
             " bytes, " + std::to_string(b.size() - at - 12) + " follow";
    const std::string_view type = b.substr(at + 4, 4);
    if (bigEndian32(b, at + 8 + length) != crc32Of(b.data() + at + 4, 4 + length))
      return "damaged: chunk '" + std::string(type) + "' at byte " + std::to_string(at) +
             ": checksum mismatch";
    if (first) {
      if (type != "IHDR" || length != 13) return "damaged: no IHDR chunk first";
      w = bigEndian32(b, at + 8);
      h = bigEndian32(b, at + 12);
      first = false;
    }
    if (type == "IEND") return "";
    at += 12 + length;
  }
}

// PNM (P2, P3, P5, P6): width, height and maxval; the binary ones must hold their pixels.
std::string pnmProblem(std::string_view b, double& w, double& h) {
  size_t at = 2;
  double numbers[3];
  for (double& n : numbers) {
    while (at < b.size() && (std::isspace(static_cast<unsigned char>(b[at])) || b[at] == '#')) {
      if (b[at] == '#')
        while (at < b.size() && b[at] != '\n') ++at;
      else
        ++at;
    }
    if (at >= b.size() || !std::isdigit(static_cast<unsigned char>(b[at])))
      return "damaged: the header's width, height and maximum value expected";
    n = 0;
    for (; at < b.size() && std::isdigit(static_cast<unsigned char>(b[at])); ++at)
      n = std::min(n * 10 + (b[at] - '0'), 1e15);
  }
  w = numbers[0];
  h = numbers[1];
  if (!(numbers[2] >= 1 && numbers[2] <= 65535)) return "damaged: maximum value not in [1, 65535]";
  if (b[1] == '5' || b[1] == '6') {
    const double channels = b[1] == '6' ? 3 : 1, depth = numbers[2] > 255 ? 2 : 1;
    const double need = w * h * channels * depth;
    const double have = static_cast<double>(b.size()) - static_cast<double>(at) - 1;
    if (have < need)
      return "truncated: " + std::to_string(static_cast<long long>(std::max(have, 0.0))) +
             " bytes of pixels, " + std::to_string(static_cast<long long>(std::min(need, 1e15))) +
             " expected";
  }
  return "";
}

// OpenCV's decoders print their exceptions to std::cerr: kept from the user while decoding.
class QuietCerr {
 public:
  QuietCerr() : saved_(std::cerr.rdbuf(sink_.rdbuf())) {}
  ~QuietCerr() { std::cerr.rdbuf(saved_); }
  QuietCerr(const QuietCerr&) = delete;
  QuietCerr& operator=(const QuietCerr&) = delete;

 private:
  std::ostringstream sink_;
  std::streambuf* saved_;
};

}  // namespace

cv::Mat decodeImage(std::string_view bytes, int flags, const std::string& name, double max_pixels) {
  static constexpr char kPng[] = "\x89PNG\r\n\x1a\n";
  double w = -1, h = -1;
  std::string problem;
  if (bytes.size() >= 8 && bytes.substr(0, 8) == std::string_view(kPng, 8))
    problem = pngProblem(bytes, w, h);
  else if (bytes.size() >= 2 && bytes[0] == 'P' &&
           std::string_view("2356").find(bytes[1]) != std::string_view::npos)
    problem = pnmProblem(bytes, w, h);
  if (w >= 0 && !(w >= 1 && h >= 1 && w * h <= max_pixels))
    throw ConfigError(name + ": expected an image of at most " +
                      std::to_string(static_cast<long long>(max_pixels)) + " pixels, got " +
                      sizeText(w, h));
  if (!problem.empty()) throw ConfigError(name + ": " + problem);
  if (bytes.empty()) throw ConfigError(name + ": an empty file, expected an image");
  if (bytes.size() > static_cast<size_t>(std::numeric_limits<int>::max()))
    throw ConfigError(name + ": a file of over 2 GB, expected an image");
  cv::Mat img;
  {
    const QuietCerr quiet;
    try {
      img = cv::imdecode(
          cv::Mat(1, static_cast<int>(bytes.size()), CV_8U, const_cast<char*>(bytes.data())),
          flags);
    } catch (const cv::Exception&) {
      img.release();
    }
  }
  if (img.empty()) throw ConfigError(name + ": cannot decode the image");
  return img;
}

cv::Mat readImage(const std::string& path, int flags, double max_pixels) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(path + ": cannot open the image");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return decodeImage(bytes.str(), flags, path, max_pixels);
}

}  // namespace coopmap
