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
  // > 0: also align each stretch of this many entries (end to end) to the map, starting at
  // its logged poses, and report how far the alignments move them (stretches.csv in
  // out_dir: one row per stretch). With exact poses (a run with --odometry perfect) that is
  // the scan alignment's own error.
  int align_stretch = 0;
};

// How far the stretches' alignments moved them, at each stretch's middle pose.
struct StretchAlignmentStats {
  int stretches = 0, aligned = 0;  // tried; of them, alignments that succeeded
  double rms_m = 0.0, rms_deg = 0.0;
  double median_m = 0.0, median_deg = 0.0;
  double p90_m = 0.0, p90_deg = 0.0;
  double mean_deg = 0.0;  // signed: a bias turning the stretches one way
};

struct TraverseSummary {
  std::string robot;
  size_t entries = 0, used = 0;
  double duration_s = 0.0, path_length_m = 0.0;
  size_t turns = 0, straights = 0;  // entries by motion segment
  StretchAlignmentStats alignment;  // with align_stretch > 0
};

// Throws std::runtime_error for a bad log or unwritable outputs, std::invalid_argument for
// a bad range.
TraverseSummary runTraverse(const TraverseOptions& options);

// Prints what the log holds and, with align_stretch, how far the stretches' alignments moved.
void printTraverseSummary(const TraverseOptions& options, const TraverseSummary& summary);

}  // namespace coopmap
