#include "core/perception/radial_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/stereo/trinocular_matcher.h"

namespace coopmap {

void RadialMapConfig::validate() const {
  auto bad = [](const std::string& f, const std::string& e, double v) {
    throw std::invalid_argument("radial map config: field '" + f + "': expected " + e + ", got " +
                                std::to_string(v));
  };
  if (!(min_height >= 0.0)) bad("min_height", "a number >= 0", min_height);
  if (!(max_range > 0.0)) bad("max_range", "a positive number", max_range);
  if (min_support < 1) bad("min_support", "an integer >= 1", min_support);
  if (beyond_support < 1) bad("beyond_support", "an integer >= 1", beyond_support);
  if (!(support_tolerance > 0.0)) bad("support_tolerance", "a positive number", support_tolerance);
  if (!(spike_ratio >= 0.0 && spike_ratio < 1.0))
    bad("spike_ratio", "a number in [0, 1)", spike_ratio);
  if (!(disparity_sigma > 0.0)) bad("disparity_sigma", "a positive number", disparity_sigma);
  if (!(floor_edge_depth >= 0.0))
    bad("floor_edge_depth", "a number >= 0 (0: off)", floor_edge_depth);
  if (!(floor_tolerance > 0.0)) bad("floor_tolerance", "a positive number", floor_tolerance);
  if (!(floor_edge_sigma >= 0.0)) bad("floor_edge_sigma", "a number >= 0", floor_edge_sigma);
}

namespace {

// Sorts `disparities` nearest first and finds the nearest run of at least `min_support`
// that agree within `tolerance` of its first: (its first index, its length), or (0, 0).
std::pair<size_t, size_t> nearestAgreeing(std::vector<float>& disparities, double tolerance,
                                          int min_support) {
  std::sort(disparities.begin(), disparities.end(), std::greater<float>());
  for (size_t i = 0; i < disparities.size(); ++i) {
    size_t support = 0;
    for (size_t j = i; j < disparities.size() && disparities[i] - disparities[j] <= tolerance; ++j)
      ++support;
    if (static_cast<int>(support) >= min_support) return {i, support};
  }
  return {0, 0};
}

}  // namespace

RadialMap buildRadialMap(const cv::Mat& disparity, const RobotDescription& robot,
                         const RadialMapConfig& config, double stamp, const Pose2& odometry) {
  const TrinocularRig& rig = robot.rig;
  const CameraIntrinsics& k = rig.intrinsics;
  if (disparity.type() != CV_32F || disparity.cols != k.width || disparity.rows != k.height)
    throw std::invalid_argument("buildRadialMap: disparity must be CV_32F of the rig size");
  const double fb = k.fx * rig.referenceBaseline();
  const double cam_z = rig.mount_position.z();
  const double min_disp_in_range = fb / config.max_range;

  RadialMap out;
  out.stamp = stamp;
  out.odometry = odometry;
  out.sensor_origin = rig.mount_position.head<2>();
  out.max_range = config.max_range;
  out.readings.resize(k.width);

  std::vector<float> band, far;
  band.reserve(k.height);
  far.reserve(k.height);
  for (int u = 0; u < k.width; ++u) {
    RadialReading& r = out.readings[u];
    const double slope = (u - k.cx) / k.fx;  // X/Z in the camera frame
    r.bearing = std::atan2(-slope, 1.0);
    band.clear();
    far.clear();
    for (int v = 0; v < k.height; ++v) {
      const float d = disparity.at<float>(v, u);
      if (!(d > 0.0f)) continue;
      const double z = fb / d;
      const double height = cam_z - (v - k.cy) * z / k.fy;
      if (height < config.min_height || height > robot.swept_height) continue;
      if (d < min_disp_in_range) {
        far.push_back(d);
        continue;
      }
      band.push_back(d);
    }
    // The nearest return that enough pixels of the column agree with.
    if (const auto [first, support] =
            nearestAgreeing(band, config.support_tolerance, config.min_support);
        support > 0) {
      double sum = 0.0;
      for (size_t j = first; j < first + support; ++j) sum += band[j];
      r.disparity = sum / support;
      const double z = fb / r.disparity;
      r.range = z * std::sqrt(1.0 + slope * slope);
      r.sigma = z * z / fb * config.disparity_sigma * std::sqrt(1.0 + slope * slope);
      r.kind = RadialKind::kHit;
    }
    // Beyond max_range where beyond_support of the column's far returns agree.
    if (r.kind == RadialKind::kNone &&
        nearestAgreeing(far, config.support_tolerance, config.beyond_support).second > 0) {
      r.kind = RadialKind::kBeyond;
      r.range = config.max_range;
    }
    if (r.kind == RadialKind::kNone && config.floor_edge_depth > 0.0) {
      // The farthest floor row that the rows below it back up (3 of 5 on the floor); the
      // median disparity of those rows is where the floor ends. (Rows of a textureless wall
      // just above its foot match the foot's disparity, so the rows themselves are no
      // measure of the range, and the smallest disparities put it too far.)
      const auto onFloor = [&](int v) {
        const float d = disparity.at<float>(v, u);
        return d > 0.0f && std::abs(d - fb * (v - k.cy) / (k.fy * cam_z)) <= config.floor_tolerance;
      };
      for (int v = static_cast<int>(std::ceil(k.cy)) + 1; v < k.height; ++v) {
        if (!onFloor(v)) continue;
        band.clear();
        for (int w = v; w < std::min(k.height, v + 5); ++w)
          if (onFloor(w)) band.push_back(disparity.at<float>(w, u));
        if (band.size() < 3) continue;
        std::nth_element(band.begin(), band.begin() + band.size() / 2, band.end());
        const double d = band[band.size() / 2];
        const double z = fb / d;
        if (z <= config.floor_edge_depth) {
          r.disparity = d;
          r.range = z * std::sqrt(1.0 + slope * slope);
          r.sigma = std::max(config.floor_edge_sigma,
                             z * z / fb * config.disparity_sigma * std::sqrt(1.0 + slope * slope));
          r.kind = RadialKind::kHit;
          r.floor_edge = true;
        }
        break;
      }
    }
  }
  removeSpikes(out, config.spike_ratio);
  return out;
}

int removeSpikes(RadialMap& map, double spike_ratio) {
  int removed = 0;
  std::vector<RadialReading>& rs = map.readings;
  for (size_t i = 1; i + 1 < rs.size(); ++i) {
    const RadialReading &a = rs[i - 1], &b = rs[i], &c = rs[i + 1];
    if (b.kind != RadialKind::kHit) continue;
    const double ra = a.kind == RadialKind::kNone ? -1.0 : a.range;
    const double rc = c.kind == RadialKind::kNone ? -1.0 : c.range;
    if (ra < 0.0 || rc < 0.0) continue;
    const double near = std::min(ra, rc);
    if (b.range < near * (1.0 - spike_ratio)) {
      rs[i].kind = RadialKind::kNone;
      rs[i].floor_edge = false;
      ++removed;
    }
  }
  return removed;
}

}  // namespace coopmap
