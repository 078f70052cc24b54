// Little-endian binary encoding helpers for coopmap's own file formats (traverse logs,
// shared-map snapshots): append values to a byte string, read them back with bounds
// known in advance, and CRC-32 (zlib) checksums.
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <string>

namespace coopmap {

static_assert(std::endian::native == std::endian::little,
              "coopmap's binary formats are written by little-endian hosts");

// CRC-32 (as zlib's crc32) of n bytes.
uint32_t crc32Of(const char* data, size_t n);

class ByteWriter {
 public:
  template <typename T>
  void put(T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    out.append(b, sizeof(T));
  }
  void putBytes(const std::string& s) { out += s; }
  std::string out;
};

// Reads values from bytes[begin, end); callers check left() before reading.
class ByteReader {
 public:
  ByteReader(const std::string& bytes, size_t begin, size_t end)
      : b_(bytes), pos_(begin), end_(end) {}
  template <typename T>
  T get() {
    T v;
    std::memcpy(&v, b_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  void getBytes(void* dst, size_t n) {
    std::memcpy(dst, b_.data() + pos_, n);
    pos_ += n;
  }
  size_t left() const { return end_ - pos_; }
  size_t position() const { return pos_; }

 private:
  const std::string& b_;
  size_t pos_, end_;
};

}  // namespace coopmap
