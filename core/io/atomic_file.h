// Writing files so that readers never see half a file: write a temp file, then rename.
#pragma once

#include <string>
#include <string_view>

namespace coopmap {

// Writes `bytes` to `path` atomically (temp file in the same folder, fsync, rename).
// Throws std::runtime_error naming the path on failure.
void writeFileAtomic(const std::string& path, std::string_view bytes);

// Reads a whole file; throws std::runtime_error naming the path if it cannot.
std::string readFile(const std::string& path);

}  // namespace coopmap
