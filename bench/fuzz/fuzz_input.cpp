#include "bench/fuzz/fuzz_input.h"

#include <unistd.h>

#include <fstream>
#include <stdexcept>

namespace coopmap::fuzz {

namespace fs = std::filesystem;

void expectCleanError(const std::function<void()>& read) {
  try {
    read();
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
}

std::map<std::string, std::string> splitFiles(std::string_view input) {
  std::map<std::string, std::string> files;
  constexpr std::string_view kOpen = "=== ", kClose = " ===\n";
  std::string* current = nullptr;
  size_t at = 0;
  while (at < input.size()) {
    size_t end = input.find('\n', at);
    end = end == std::string_view::npos ? input.size() : end + 1;
    const std::string_view line = input.substr(at, end - at);
    if (line.size() > kOpen.size() + kClose.size() && line.substr(0, kOpen.size()) == kOpen &&
        line.substr(line.size() - kClose.size()) == kClose) {
      std::string name(line.substr(kOpen.size(), line.size() - kOpen.size() - kClose.size()));
      // Only plain relative paths: the input never writes outside its folder.
      const bool plain = !name.empty() && name.front() != '/' &&
                         name.find("..") == std::string::npos &&
                         name.find('\0') == std::string::npos;
      current = plain ? &files[name] : nullptr;
    } else if (current) {
      current->append(line);
    }
    at = end;
  }
  return files;
}

fs::path writeFiles(const std::map<std::string, std::string>& files) {
  static const fs::path dir = [] {
    const fs::path base = fs::exists("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
    return base / ("coopmap_fuzz_" + std::to_string(::getpid()));
  }();
  std::error_code ec;
  fs::remove_all(dir, ec);
  fs::create_directories(dir);
  for (const auto& [name, bytes] : files) {
    const fs::path path = dir / name;
    fs::create_directories(path.parent_path(), ec);
    std::ofstream(path, std::ios::binary)
        .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  return dir;
}

}  // namespace coopmap::fuzz
