// TUM trajectory files: "timestamp tx ty tz qx qy qz qw" per line, for evo and friends.
#pragma once

#include <string>
#include <vector>

#include "core/geometry/pose2.h"

namespace coopmap {

struct StampedPose2 {
  double stamp = 0.0;  // s
  Pose2 pose;          // planar pose; z = 0, rotation about +z
};

// Formats a trajectory in TUM format (header comment first).
std::string formatTum(const std::vector<StampedPose2>& trajectory, const std::string& comment);

// Writes a trajectory in TUM format atomically.
void writeTum(const std::string& path, const std::vector<StampedPose2>& trajectory,
              const std::string& comment);

// Parses a TUM trajectory (comment lines start with '#'; the heading is the rotation's yaw).
// Throws std::runtime_error naming `source` and the line for a line that is not 8 numbers
// or a timestamp earlier than the one before.
std::vector<StampedPose2> parseTum(const std::string& text, const std::string& source);
// Reads a TUM file (parseTum; std::runtime_error naming the file if it cannot be read).
std::vector<StampedPose2> readTum(const std::string& path);

// The pose stamped `stamp` (within a millisecond: TUM files keep microseconds) in a
// trajectory in time order, or nullptr if it has none.
const Pose2* tumPoseAt(const std::vector<StampedPose2>& trajectory, double stamp);

}  // namespace coopmap
