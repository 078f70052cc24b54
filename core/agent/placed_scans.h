// Internals shared by the cooperation layer's files (core/agent/cooperation*.cpp): radial
// maps placed at other poses for the aligner, and how far a correction moves a pose.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "core/correction/traverse_log.h"
#include "core/geometry/pose2.h"

namespace coopmap::detail {

// Radial maps [begin, end) of a log placed at other poses (the corrected ones), for the
// aligner, which places each scan at its own pose.
struct PlacedScans {
  PlacedScans(const TraverseLog& log, const std::vector<Pose2>& poses, size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      maps.push_back(log.entries[i].scan);
      maps.back().odometry = poses[i];
    }
    for (const RadialMap& m : maps) pointers.push_back(&m);
  }
  PlacedScans(const PlacedScans&) = delete;
  PlacedScans& operator=(const PlacedScans&) = delete;
  std::vector<RadialMap> maps;
  std::vector<const RadialMap*> pointers;
};

// Whether an alignment's correction (map frame) moves `pose` by at most `max_m` and turns it
// by at most `max_rad` (the post gate asks at a stretch's middle, the closures at the map's
// origin: see mapClosures).
inline bool movesWithin(const Pose2& correction, const Pose2& pose, double max_m, double max_rad) {
  const Pose2 moved = correction * pose;
  return (moved.translation() - pose.translation()).norm() <= max_m &&
         std::abs(wrapAngle(moved.theta - pose.theta)) <= max_rad;
}

}  // namespace coopmap::detail
