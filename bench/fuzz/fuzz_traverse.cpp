// libFuzzer target: the traverse log reader (core/correction/traverse_log.h), on log bytes.
// Mutated bytes rarely keep their CRC-32s, and the reader stops at the first mismatch: for
// inputs whose first byte is even the target first makes every checksum match what it
// covers, so that the values behind them (poses, ranges, counts, stamps) are exercised too.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "bench/fuzz/fuzz_input.h"
#include "core/correction/traverse_log.h"
#include "core/io/binary_io.h"

namespace {

uint32_t u32At(const std::string& b, size_t at) {
  uint32_t v = 0;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

void putCrc(std::string& b, size_t from, size_t to) {
  const uint32_t c = coopmap::crc32Of(b.data() + from, to - from);
  std::memcpy(b.data() + to, &c, 4);
}

// Rewrites the header's, each record's and the end record's checksum in place, as far as
// the layout (traverse_log.h) can be followed.
void repairChecksums(std::string& b) {
  if (b.size() < 16) return;
  const size_t name = u32At(b, 12);
  size_t pos = 16 + name;
  if (name > b.size() || pos + 4 > b.size()) return;
  putCrc(b, 0, pos);
  pos += 4;
  while (pos + 8 <= b.size()) {
    const uint32_t magic = u32At(b, pos), length = u32At(b, pos + 4);
    if (magic == 0x21444E45u) {  // "END!"
      if (pos + 12 <= b.size()) putCrc(b, pos, pos + 8);
      return;
    }
    if (length > b.size() - pos - 8 || pos + 8 + length + 4 > b.size()) return;
    putCrc(b, pos + 8, pos + 8 + length);
    pos += 8 + length + 4;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  if (data[0] % 2 == 0) repairChecksums(bytes);
  coopmap::fuzz::expectCleanError([&] { coopmap::decodeTraverseLog(bytes, "fuzz.traverse"); });
  return 0;
}
