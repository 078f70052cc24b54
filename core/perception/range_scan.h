// Planar range scans (lasers) as radial maps: a radial map is already a 1D range scan, so a
// laser feeds the same occupancy grid, traverse log and corner detector as stereo does.
#pragma once

#include "core/perception/radial_map.h"
#include "core/robot/robot_interface.h"

namespace coopmap {

struct RangeScanConfig {
  double max_range = 0.0;         // m, usable range; 0: the scan's own max_range. Hits farther than
                                  // this only clear free space up to it
  double min_range = 0.02;        // m; nearer readings are invalid (no information)
  bool free_on_no_return = true;  // "no return" readings clear free space up to max_range
  double min_sigma = 0.0;         // m, floor under the scan's range_sigma

  void validate() const;  // throws std::invalid_argument naming the field
};

// Converts a scan to a radial map, one reading per beam in beam order: a valid range within
// the usable range is a kHit with the scan's sigma; a farther one, or (with
// free_on_no_return) one at the sensor's max_range, is kBeyond (free up to the usable range);
// a reading below min_range, not finite, or a no-return without free_on_no_return is kNone.
// Throws std::invalid_argument for a scan without a positive max_range or with a
// non-finite angle.
RadialMap radialMapFromScan(const RangeScan& scan, const RangeScanConfig& config = {});

}  // namespace coopmap
