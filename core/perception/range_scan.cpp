#include "core/perception/range_scan.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace coopmap {

void RangeScanConfig::validate() const {
  auto bad = [](const std::string& f, const std::string& e, double v) {
    throw std::invalid_argument("range scan config: field '" + f + "': expected " + e + ", got " +
                                std::to_string(v));
  };
  if (!(max_range >= 0.0) || !std::isfinite(max_range))
    bad("max_range", "a number >= 0 (0: the scan's)", max_range);
  if (!(min_range >= 0.0) || !std::isfinite(min_range))
    bad("min_range", "a number >= 0", min_range);
  if (max_range > 0.0 && min_range >= max_range)
    bad("min_range", "a number below max_range", min_range);
  if (!(min_sigma >= 0.0) || !std::isfinite(min_sigma))
    bad("min_sigma", "a number >= 0", min_sigma);
}

RadialMap radialMapFromScan(const RangeScan& scan, const RangeScanConfig& config) {
  config.validate();
  if (!(scan.max_range > 0.0) || !std::isfinite(scan.max_range))
    throw std::invalid_argument("radialMapFromScan: scan max_range must be positive, got " +
                                std::to_string(scan.max_range));
  if (!std::isfinite(scan.start_angle) || !std::isfinite(scan.angular_resolution))
    throw std::invalid_argument("radialMapFromScan: scan angles must be finite");
  const double usable =
      config.max_range > 0.0 ? std::min(config.max_range, scan.max_range) : scan.max_range;
  const double sigma = std::max(config.min_sigma, scan.range_sigma);

  RadialMap out;
  out.stamp = scan.stamp;
  out.odometry = scan.odometry;
  out.sensor_origin = scan.sensor_origin;
  out.max_range = usable;
  out.readings.resize(scan.ranges.size());
  for (size_t i = 0; i < scan.ranges.size(); ++i) {
    RadialReading& r = out.readings[i];
    r.bearing = wrapAngle(scan.bearing(i));
    const double range = scan.ranges[i];
    if (!std::isfinite(range) || range < config.min_range) continue;  // kNone
    if (range >= scan.max_range) {
      if (!config.free_on_no_return) continue;
      r.kind = RadialKind::kBeyond;
      r.range = usable;
    } else if (range > usable) {
      r.kind = RadialKind::kBeyond;
      r.range = usable;
    } else {
      r.kind = RadialKind::kHit;
      r.range = range;
      r.sigma = sigma;
    }
  }
  return out;
}

}  // namespace coopmap
