// A world run's outputs, written into a folder: per robot its map (map_<robot>.pgm/.yaml,
// ROS map_server), pictures of it and of it against the truth, its trajectories (TUM: ground
// truth, odometry, estimate, corrected) and traverse log; the shared maps and theirs;
// timeline.csv, metrics.json and report.html. Formats: docs/formats.md.
#pragma once

#include <string>

#include "sim/runner/world_run.h"

namespace coopmap {

// Writes `result` into `dir` (created if missing), each file atomically. Throws
// std::runtime_error naming the file when one cannot be written.
void writeRunOutputs(const std::string& dir, const RunResult& result);

}  // namespace coopmap
