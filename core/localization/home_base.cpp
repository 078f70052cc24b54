#include "core/localization/home_base.h"

#include <algorithm>
#include <cmath>

namespace coopmap {

OccupancyGrid localMap(const std::vector<RadialMap>& scans, const MapLimits& limits,
                       const OccupancyConfig& config) {
  OccupancyGrid grid(limits, config);
  for (const RadialMap& scan : scans) grid.insert(scan, scan.odometry);
  return grid;
}

HomeBaseRegistration registerHomeBase(const CornerDetector& detector, const Eigen::Vector2d& first,
                                      const Eigen::Vector2d& second, double search_radius) {
  HomeBaseRegistration r;
  const CornerSearch a = detector.findNear(first, search_radius);
  if (a.status != CornerStatus::kOk) {
    r.status = a.status;
    return r;
  }
  const CornerSearch b = detector.findNear(second, search_radius);
  if (b.status != CornerStatus::kOk) {
    r.status = b.status;
    return r;
  }
  r.home = HomeBase{a.corners.front(), b.corners.front()};
  return r;
}

HomeBaseFix localizeAtHomeBase(const CornerDetector& detector, const HomeBase& home,
                               const Pose2& odometry, double search_radius,
                               double max_separation_error) {
  HomeBaseFix fix;
  const CornerSearch a = detector.findNear(home.first.position, search_radius, home.first.heading);
  const CornerSearch b =
      detector.findNear(home.second.position, search_radius, home.second.heading);
  if (a.status != CornerStatus::kOk || b.status != CornerStatus::kOk) return fix;
  fix.first = a.corners.front();
  fix.second = b.corners.front();
  const Eigen::Vector2d reg = home.second.position - home.first.position;
  const Eigen::Vector2d obs = fix.second.position - fix.first.position;
  fix.separation_error = std::abs(obs.norm() - reg.norm());
  if (fix.separation_error > max_separation_error) {
    fix.status = HomeBaseStatus::kGeometryMismatch;
    return fix;
  }
  // Heading from the line joining the corners; translation that puts their midpoint back.
  const double dtheta = std::atan2(reg.y(), reg.x()) - std::atan2(obs.y(), obs.x());
  const double c = std::cos(dtheta), s = std::sin(dtheta);
  const Eigen::Vector2d mid_obs = 0.5 * (fix.first.position + fix.second.position);
  const Eigen::Vector2d mid_reg = 0.5 * (home.first.position + home.second.position);
  const Eigen::Vector2d rotated(c * mid_obs.x() - s * mid_obs.y(),
                                s * mid_obs.x() + c * mid_obs.y());
  const Eigen::Vector2d t = mid_reg - rotated;
  fix.correction = Pose2(t.x(), t.y(), wrapAngle(dtheta));
  fix.pose = fix.correction * odometry;
  // Uncertainty: each corner's position to about its RMS / sqrt(points) cells; both ends of
  // the joining line add to the heading error.
  const double res = detector.limits().resolution;
  fix.rms = std::max(fix.first.rms, fix.second.rms);
  const double per_corner = std::max(0.1, fix.rms / 4.0) * res;  // m
  fix.sigma_xy = per_corner / std::sqrt(2.0);
  fix.sigma_theta = std::sqrt(2.0) * per_corner / std::max(obs.norm(), 1e-6);
  fix.status = HomeBaseStatus::kOk;
  return fix;
}

}  // namespace coopmap
