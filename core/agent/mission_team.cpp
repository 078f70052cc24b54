// The mission's dealings with teammates (core/agent/mission.h): where they are and what
// they have claimed, a teammate in the way ahead, and passages (doors) taken one robot at a
// time.
#include "core/agent/mission.h"

#include <algorithm>
#include <cmath>

namespace coopmap {

void MissionAgent::setTeammates(std::vector<Eigen::Vector2d> positions, bool priority) {
  teammates_ = std::move(positions);
  priority_ = priority;
}

void MissionAgent::setTeammateGoals(const std::vector<Eigen::Vector2d>& goals) {
  for (const Eigen::Vector2d& g : goals) {
    const bool known = std::any_of(claims_.begin(), claims_.end(), [&](const Eigen::Vector2d& c) {
      return (c - g).norm() < config_.frontiers.blacklist_radius;
    });
    if (!known) claims_.push_back(g);
  }
}

std::vector<Eigen::Vector2d> MissionAgent::wayAhead(const Pose2& pose) const {
  std::vector<Eigen::Vector2d> way{pose.translation()};
  if (follower_ && path_.waypoints.size() >= 2) {
    for (size_t k = std::min(follower_->nextWaypoint() + 1, path_.waypoints.size() - 1);
         k < path_.waypoints.size(); ++k)
      way.push_back(path_.waypoints[k]);
  } else {
    way.push_back(target_.translation());
  }
  return way;
}

std::optional<Eigen::Vector2d> MissionAgent::passageAhead(const Pose2& pose,
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
  const std::vector<Eigen::Vector2d> way = wayAhead(pose);
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

bool MissionAgent::passageHeld(const Pose2& pose, const OccupancyGrid& map) const {
  bool here = false;
  const std::optional<Eigen::Vector2d> passage = passageAhead(pose, map, &here);
  if (!passage || here) return false;
  const double mine = (*passage - pose.translation()).norm();
  for (const Eigen::Vector2d& t : teammates_) {
    const double theirs = (*passage - t).norm();
    if (theirs < config_.passage_radius && (theirs < mine || (theirs == mine && !priority_)))
      return true;
  }
  return false;
}

bool MissionAgent::teammateAhead(const Pose2& pose) const {
  // The way ahead: the rest of the path being followed (or straight to the target).
  const std::vector<Eigen::Vector2d> way = wayAhead(pose);
  // A teammate stops this robot only where the way passes it closer than the planning map's
  // disc allows: once planned around a teammate standing still, the robot drives on.
  const double clear = 0.9 * (config_.team_radius + config_.planning.robot_radius);
  for (const Eigen::Vector2d& p : teammates_) {
    const Eigen::Vector2d to = p - pose.translation();
    if (to.norm() < config_.team_distance &&
        std::abs(wrapAngle(std::atan2(to.y(), to.x()) - pose.theta)) < config_.team_half_angle &&
        (to.norm() < config_.team_close || nearWay(way, p, clear)))
      return true;
  }
  return false;
}

void MissionAgent::trackTeammates(double now) {
  if (teammates_.size() != teammates_before_.size()) {
    teammates_before_ = teammates_;
    teammates_before_at_ = now;
    teammate_velocities_.assign(teammates_.size(), Eigen::Vector2d::Zero());
    return;
  }
  if (now - teammates_before_at_ < config_.team_velocity_s) return;
  for (size_t k = 0; k < teammates_.size(); ++k)
    teammate_velocities_[k] = (teammates_[k] - teammates_before_[k]) / (now - teammates_before_at_);
  teammates_before_ = teammates_;
  teammates_before_at_ = now;
}

bool MissionAgent::teammateInTheWay(const Pose2& pose) const {
  if (teammateAhead(pose)) return true;
  if (priority_ || teammate_velocities_.size() != teammates_.size()) return false;
  // Closest approach at constant velocities: this robot's as commanded, along its heading.
  const Eigen::Vector2d mine =
      last_command_.linear * Eigen::Vector2d(std::cos(pose.theta), std::sin(pose.theta));
  const double clear = config_.team_radius + config_.planning.robot_radius;
  for (size_t k = 0; k < teammates_.size(); ++k) {
    const Eigen::Vector2d r = teammates_[k] - pose.translation();
    const Eigen::Vector2d w = teammate_velocities_[k] - mine;
    if (r.dot(w) >= 0.0) continue;  // not closing in
    const double t = std::min(-r.dot(w) / w.squaredNorm(), config_.team_horizon_s);
    if ((r + t * w).norm() < clear) return true;
  }
  return false;
}

}  // namespace coopmap
