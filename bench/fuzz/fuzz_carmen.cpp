// libFuzzer target: the CARMEN log reader (core/io/carmen_log.h), on log text.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "bench/fuzz/fuzz_input.h"
#include "core/io/carmen_log.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  coopmap::fuzz::expectCleanError([&] { coopmap::parseCarmenLog(text, "fuzz.log"); });
  return 0;
}
