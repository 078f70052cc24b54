#include "core/io/binary_io.h"

#include <zlib.h>

namespace coopmap {

uint32_t crc32Of(const char* data, size_t n) {
  return static_cast<uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(data), static_cast<uInt>(n)));
}

}  // namespace coopmap
