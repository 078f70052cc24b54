#include "core/agent/team_traffic.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/agent/mission_maps.h"

namespace coopmap {

TeamTraffic::TeamTraffic(const MissionConfig& config) : config_(config) {}

void TeamTraffic::set(std::vector<Eigen::Vector2d> positions, bool priority) {
  positions_ = std::move(positions);
  priority_ = priority;
}

void TeamTraffic::track(double now) {
  if (positions_.size() != positions_before_.size()) {
    positions_before_ = positions_;
    positions_before_at_ = now;
    velocities_.assign(positions_.size(), Eigen::Vector2d::Zero());
    return;
  }
  if (now - positions_before_at_ < config_.team_velocity_s) return;
  for (size_t k = 0; k < positions_.size(); ++k)
    velocities_[k] = (positions_[k] - positions_before_[k]) / (now - positions_before_at_);
  positions_before_ = positions_;
  positions_before_at_ = now;
}

TeamWait TeamTraffic::passageWait(double now, const Pose2& pose,
                                  const std::vector<Eigen::Vector2d>& way, const OccupancyGrid& map,
                                  bool driving) {
  if (config_.passage_width > 0.0 && driving && now >= passage_next_ &&
      passageHeld(pose, way, map)) {
    bool begins = false;
    if (passage_wait_since_ < 0.0) {
      passage_wait_since_ = now;
      ++passage_waits_;
      begins = true;
    }
    if (now - passage_wait_since_ < config_.passage_wait_s)
      return begins ? TeamWait::kNewWait : TeamWait::kWaiting;
    passage_next_ = now + config_.passage_wait_s;  // waited long enough: go, for a while
  }
  passage_wait_since_ = -1.0;
  return TeamWait::kNone;
}

TeamWait TeamTraffic::teammateWait(double now, const Pose2& pose,
                                   const std::vector<Eigen::Vector2d>& way, double linear,
                                   bool driving) {
  if (driving && teammateInTheWay(pose, way, linear)) {
    bool begins = false;
    if (team_wait_until_ < 0.0) {
      ++team_stops_;
      team_wait_until_ = now + (priority_ ? 0.25 : 1.0) * config_.team_wait_s;
      begins = true;
    }
    if (now < team_wait_until_) return begins ? TeamWait::kNewWait : TeamWait::kWaiting;
    team_wait_until_ = -1.0;
    return TeamWait::kWaitOver;
  }
  if (team_wait_until_ >= 0.0 && !teammateInTheWay(pose, way, linear)) team_wait_until_ = -1.0;
  return TeamWait::kNone;
}

std::optional<Eigen::Vector2d> TeamTraffic::passageAhead(const std::vector<Eigen::Vector2d>& way,
                                                         const OccupancyGrid& map,
                                                         bool* here) const {
  *here = false;
  const MapLimits& lim = map.limits();
  const double step = lim.resolution;
  // m to the first occupied cell from p along direction d, up to `far`.
  auto reach = [&](const Eigen::Vector2d& p, const Eigen::Vector2d& d, double far) {
    for (double s = step; s <= far; s += step) {
      const Eigen::Vector2d q = p + s * d;
      const int ix = lim.cellX(q.x()), iy = lim.cellY(q.y());
      if (!lim.contains(ix, iy) || map.state(ix, iy) == CellState::kOccupied) return s;
    }
    return far;
  };
  double along = 0.0;
  for (size_t k = 0; k + 1 < way.size() && along <= config_.passage_lookahead; ++k) {
    const Eigen::Vector2d a = way[k], ab = way[k + 1] - a;
    const double len = ab.norm();
    if (len < 1e-9) continue;
    const Eigen::Vector2d d = ab / len, side(-d.y(), d.x());
    for (double s = 0.0; s <= len && along + s <= config_.passage_lookahead; s += 2.0 * step) {
      const Eigen::Vector2d p = a + s * d;
      const double w = config_.passage_width;
      if (reach(p, side, w) + reach(p, -side, w) < w) {
        *here = along + s < 2.0 * step;
        return p;
      }
    }
    along += len;
  }
  return std::nullopt;
}

bool TeamTraffic::passageHeld(const Pose2& pose, const std::vector<Eigen::Vector2d>& way,
                              const OccupancyGrid& map) const {
  bool here = false;
  const std::optional<Eigen::Vector2d> passage = passageAhead(way, map, &here);
  if (!passage || here) return false;
  const double mine = (*passage - pose.translation()).norm();
  for (const Eigen::Vector2d& t : positions_) {
    const double theirs = (*passage - t).norm();
    if (theirs < config_.passage_radius && (theirs < mine || (theirs == mine && !priority_)))
      return true;
  }
  return false;
}

bool TeamTraffic::teammateAhead(const Pose2& pose, const std::vector<Eigen::Vector2d>& way) const {
  // A teammate stops this robot only where the way passes it closer than the planning map's
  // disc allows: once planned around a teammate standing still, the robot drives on.
  const double clear = 0.9 * (config_.team_radius + config_.planning.robot_radius);
  for (const Eigen::Vector2d& p : positions_) {
    const Eigen::Vector2d to = p - pose.translation();
    if (to.norm() < config_.team_distance &&
        std::abs(wrapAngle(std::atan2(to.y(), to.x()) - pose.theta)) < config_.team_half_angle &&
        (to.norm() < config_.team_close || nearWay(way, p, clear)))
      return true;
  }
  return false;
}

bool TeamTraffic::teammateInTheWay(const Pose2& pose, const std::vector<Eigen::Vector2d>& way,
                                   double linear) const {
  if (teammateAhead(pose, way)) return true;
  if (priority_ || velocities_.size() != positions_.size()) return false;
  // Closest approach at constant velocities: this robot's as commanded, along its heading.
  const Eigen::Vector2d mine = linear * Eigen::Vector2d(std::cos(pose.theta), std::sin(pose.theta));
  const double clear = config_.team_radius + config_.planning.robot_radius;
  for (size_t k = 0; k < positions_.size(); ++k) {
    const Eigen::Vector2d r = positions_[k] - pose.translation();
    const Eigen::Vector2d w = velocities_[k] - mine;
    if (r.dot(w) >= 0.0) continue;  // not closing in
    const double t = std::min(-r.dot(w) / w.squaredNorm(), config_.team_horizon_s);
    if ((r + t * w).norm() < clear) return true;
  }
  return false;
}

}  // namespace coopmap
