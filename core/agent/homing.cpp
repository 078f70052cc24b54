#include "core/agent/homing.h"

#include <utility>

#include "core/agent/mission_maps.h"

namespace coopmap {

Homing::Homing(const MissionConfig& config, const Pose2& home)
    : config_(config), planner_(config.planner), target_(home) {}

void Homing::startSortie(const Pose2& home) {
  target_ = home;
  bumps_ = 0;
  waits_ = 0;
}

void Homing::returnTo(const Pose2& home) {
  target_ = home;
  bumps_ = 0;
  plan_due_ = true;
}

bool Homing::planDue(double now) {
  if (!(plan_due_ || (retry_at_ >= 0.0 && now >= retry_at_))) return false;
  plan_due_ = false;
  return true;
}

bool Homing::nearHome(const Pose2& odometry) const {
  return (odometry.translation() - target_.translation()).norm() < config_.look_from_m;
}

bool Homing::blockedNearHome(const Pose2& odometry) {
  return ++bumps_ >= config_.max_return_bumps && nearHome(odometry);
}

HomeWay Homing::plan(double now, const Pose2& odometry, const PlanningMaps& maps) {
  HomeWay way;
  ends_short_ = false;
  margin_ = -1.0;
  // On a blocked cell (backed off from a bump into what it has just drawn): step off to the
  // nearest free cell first, and plan from there.
  const PlanningMap planning = maps();
  Pose2 from = odometry;
  const bool step_off = !planning.freeAt(odometry.translation());
  if (step_off)
    if (const std::optional<Eigen::Vector2d> to =
            nearestFreeCell(planning, odometry.translation(), config_.escape_radius))
      from = Pose2(to->x(), to->y(), odometry.theta);
  const Eigen::Vector2d home = target_.translation();
  PlanResult plan = planner_.plan(planning, from, home);
  if (!plan.solved()) {
    PlanResult unknown = planner_.plan(maps({.allow_unknown = true}), from, home);
    const double straight = (home - from.translation()).norm();
    if (unknown.solved() && unknown.path.length() <= config_.max_home_detour * straight + 2.0) {
      plan = std::move(unknown);
    } else if (const std::optional<Eigen::Vector2d> near =
                   nearestReachable(planning, from.translation(), home)) {
      // No short way home: as near to it as the known free space goes, and plan again there.
      plan = planner_.plan(planning, from, *near);
      if (plan.solved()) ends_short_ = true;
    }
  }
  // No way with the margin: with the least one that keeps the body off every blocked cell.
  const double least = leastMargin(maps.map().limits());
  bool squeezed = false;
  if (!plan.solved() && (home - odometry.translation()).norm() > config_.look_from_m) {
    if (least < config_.planning.margin) {
      const PlanningMap tight = maps({.margin = least});
      if (tight.freeAt(from.translation())) {
        plan = planner_.plan(tight, from, home);
        squeezed = plan.solved();
      }
    }
  }
  // Waited long with no way even so: home on the trail it drove out on (trail_after_waits).
  bool on_trail = false;
  const bool far = (home - odometry.translation()).norm() > config_.look_from_m;
  if (!plan.solved() && far && config_.trail_after_waits > 0 &&
      waits_ >= config_.trail_after_waits && maps.memory().hasTrail()) {
    const PlanningMap trail = maps({.margin = least, .trail = true});
    if (trail.freeAt(from.translation())) {
      plan = planner_.plan(trail, from, home);
      on_trail = plan.solved();
    }
  }
  on_trail_ = on_trail;
  if (plan.solved()) {
    way.path = plan.path;
    if (step_off) way.path.waypoints.insert(way.path.waypoints.begin(), odometry.translation());
    way.route = routeAlong(way.path.waypoints);
    if (squeezed || on_trail) margin_ = least;
    if (squeezed) way.event = "no way home with the planning margin: going with the least";
    if (on_trail)
      way.event = "no way home in the map after " + std::to_string(waits_) +
                  " waits: going home on the trail driven out";
    else
      waits_ = 0;
  } else if ((home - odometry.translation()).norm() <= config_.look_from_m) {
    way.route = std::vector<Waypoint>{{target_.translation(), false, 0.0, 0.0}};  // straight
  } else {
    // No way home in the map now: never straight through what it shows; wait, plan again.
    retry_at_ = now + config_.home_retry_s;
    ++waits_;
    way.event = "no way home in the map: waiting to plan again";
  }
  return way;
}

}  // namespace coopmap
