#include "core/agent/map_tracker.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace coopmap {

namespace {

// The last `n` of the latest radial maps (all of them if fewer), oldest first.
std::vector<const RadialMap*> lastScans(const std::vector<RadialMap>& latest, int n) {
  const size_t k = std::min(latest.size(), static_cast<size_t>(n));
  std::vector<const RadialMap*> scans;
  for (size_t i = latest.size() - k; i < latest.size(); ++i) scans.push_back(&latest[i]);
  return scans;
}

}  // namespace

void MapTrackerConfig::validate() const {
  auto bad = [](const char* field, const std::string& expected, double v) {
    throw std::invalid_argument(std::string("map tracker config: field '") + field +
                                "': expected " + expected + ", got " + std::to_string(v));
  };
  if (scans < 1) bad("scans", "at least 1", scans);
  if (period < 1) bad("period", "at least 1", period);
  if (!(min_inliers >= 0.0 && min_inliers <= 1.0))
    bad("min_inliers", "a share in [0, 1]", min_inliers);
  if (min_points < 1) bad("min_points", "at least 1", min_points);
  if (!(max_step_m > 0.0)) bad("max_step_m", "a positive number", max_step_m);
  if (!(max_step_rad > 0.0)) bad("max_step_rad", "a positive number", max_step_rad);
  if (!(gain > 0.0 && gain <= 1.0)) bad("gain", "a number in (0, 1]", gain);
  alignment.validate();
}

MapTracker::MapTracker(const MapTrackerConfig& config) : config_(config) { config_.validate(); }

void MapTracker::setMap(const OccupancyGrid& map) {
  aligner_.reset();
  map_ = std::make_unique<OccupancyGrid>(map);
  aligner_ = std::make_unique<ScanAligner>(*map_, config_.alignment);
}

std::optional<Pose2> MapTracker::update(const std::vector<RadialMap>& latest) {
  if (!config_.enabled || !aligner_ || latest.empty()) return std::nullopt;
  if (++calls_ % config_.period != 0) return std::nullopt;
  const std::vector<const RadialMap*> scans = lastScans(latest, config_.scans);
  ++aligned_;
  const AlignmentResult a = aligner_->align(scans, Pose2());
  if (!a.ok || a.points < config_.min_points || a.inliers < config_.min_inliers * a.points)
    return std::nullopt;
  // How far the alignment moves the latest pose.
  const Pose2& now = latest.back().odometry;
  const Pose2 target = a.correction * now;
  const double dtheta = wrapAngle(target.theta - now.theta);
  if ((target.translation() - now.translation()).norm() > config_.max_step_m ||
      std::abs(dtheta) > config_.max_step_rad)
    return std::nullopt;
  ++accepted_;
  // A share of the step, in the robot's own terms (position and heading of the latest pose).
  const Eigen::Vector2d t =
      now.translation() + config_.gain * (target.translation() - now.translation());
  const Pose2 damped(t.x(), t.y(), wrapAngle(now.theta + config_.gain * dtheta));
  return damped * now.inverse();
}

void WallHeadingConfig::validate() const {
  auto bad = [](const char* field, const std::string& expected, double v) {
    throw std::invalid_argument(std::string("wall heading config: field '") + field +
                                "': expected " + expected + ", got " + std::to_string(v));
  };
  if (!(gain >= 0.0 && gain <= 1.0)) bad("gain", "a number in [0, 1] (0: off)", gain);
  if (scans < 1) bad("scans", "at least 1", scans);
  if (period < 1) bad("period", "at least 1", period);
  if (!(max_range > 0.0)) bad("max_range", "a positive number", max_range);
  manhattan.validate();
}

WallHeadingTracker::WallHeadingTracker(const WallHeadingConfig& config) : config_(config) {
  config_.validate();
}

std::optional<Pose2> WallHeadingTracker::update(const std::vector<RadialMap>& latest) {
  if (!enabled() || latest.empty()) return std::nullopt;
  if (++calls_ % config_.period != 0) return std::nullopt;
  const std::vector<const RadialMap*> scans = lastScans(latest, config_.scans);
  ++fitted_;
  const std::optional<ManhattanFit> fit =
      manhattanTurn(hitPoints(scans, config_.max_range), config_.manhattan);
  if (!fit) return std::nullopt;
  ++turned_;
  // The walls are turned by the heading's error: turn the estimate back by a share of it,
  // about where the robot is, so its position stays.
  const Pose2& now = latest.back().odometry;
  return Pose2(now.x, now.y, -config_.gain * fit->turn_rad) * Pose2(-now.x, -now.y, 0.0);
}

}  // namespace coopmap
