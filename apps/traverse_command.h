// `coopmap traverse LOG`: rebuilds a map from a saved traverse log (all entries or a range)
// at the logged odometry poses, and says what the log holds.
#pragma once

#include <string>

namespace coopmap {

struct TraverseOptions {
  std::string log_file;
  std::string out_dir;       // map.{pgm,yaml,png} go here
  long first = 0;            // first entry used
  long last = -1;            // last entry used; -1: the end
  double resolution = 0.05;  // m per cell
};

struct TraverseSummary {
  std::string robot;
  size_t entries = 0, used = 0;
  double duration_s = 0.0, path_length_m = 0.0;
  size_t turns = 0, straights = 0;  // entries by motion segment
};

// Throws std::runtime_error for a bad log or unwritable outputs, std::invalid_argument for
// a bad range.
TraverseSummary runTraverse(const TraverseOptions& options);

}  // namespace coopmap
