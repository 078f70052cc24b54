// Small worlds for scenario tests: the textures they share, one B-14 at the origin facing
// +x, written to a temporary file.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <utility>

#include <unistd.h>

namespace coopmap::test_support {

// A world file in the temporary folder, removed when this goes out of scope (each ctest run
// had left the scenario tests' worlds behind in /tmp).
class TestWorldFile {
 public:
  explicit TestWorldFile(std::string path) : path_(std::move(path)) {}
  ~TestWorldFile() {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
  }
  TestWorldFile(const TestWorldFile&) = delete;
  TestWorldFile& operator=(const TestWorldFile&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// Writes a world named `name` with the common textures (carpet, poster, wood), the given
// YAML body (floor, walls, doors, home_base, people ...) and one robot "r" at the origin
// with the given route (YAML flow list, may be empty), then `more_robots` (YAML list items
// of the robots key, may be empty). Returns the file, whose path holds the process id:
// ctest runs each test in its own process, two at a time, and two tests of one file that
// write different worlds under one name must not read each other's.
inline TestWorldFile writeTestWorld(const std::string& name, const std::string& body,
                                    const std::string& route = "",
                                    const std::string& more_robots = "") {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("coopmap_test_" + name + "_" + std::to_string(::getpid()) + ".yaml"))
                               .string();
  std::ofstream(path) << "name: " << name << R"(
textures:
  carpet: {type: noise, tile: 2.0, feature: 0.03, mean: 105, contrast: 30}
  poster: {type: posters, tile: 2.5, feature: 0.04, mean: 128, contrast: 70}
  wood: {type: noise, tile: 1.0, feature: 0.02, mean: 140, contrast: 55}
)" << body << R"(
robots:
  - name: r
    model: )" << COOPMAP_SOURCE_DIR
                      << "/robots/b14/b14.yaml\n    start: {position: [0, 0], heading_deg: 0}\n"
                      << (route.empty() ? "" : "    route: [" + route + "]\n") << more_robots;
  return TestWorldFile(path);
}

}  // namespace coopmap::test_support
