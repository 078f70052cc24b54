#include "core/agent/exploration_goals.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/agent/mission_maps.h"

namespace coopmap {

ExplorationGoals::ExplorationGoals(const MissionConfig& config)
    : config_(config), explorer_(config.frontiers, config.planner), planner_(config.planner) {}

GoalChoice ExplorationGoals::choose(double now, const Pose2& odometry, const PlanningMaps& maps,
                                    double travelled) {
  GoalChoice choice;
  // Goals by the map: what was just seen (a person, a teammate passing) is no reason to end
  // the exploration or give a frontier up. The path to the goal goes round it, if it can.
  const PlanningMap planning = maps({.recent = false});
  if (!planning.freeAt(odometry.translation())) {
    // Something seen too close (a stereo mismatch, a person passing) leaves the robot on a
    // cell the planner will not start from: step to the nearest free one first.
    const std::optional<Eigen::Vector2d> to =
        nearestFreeCell(planning, odometry.translation(), config_.escape_radius);
    if (to && !escaping_) {
      escaping_ = true;
      has_goal_ = false;
      choice.kind = GoalChoice::Kind::kStepOff;
      choice.route = {ontoCell(*to, planning.limits().resolution)};
      choice.event = "stepping off a blocked cell";
      return choice;
    }
  }
  escaping_ = false;
  const ExploreStep step = explorer_.next(maps.map(), planning, odometry, claims_);
  choice.kind = GoalChoice::Kind::kGoHome;
  if (step.status == ExploreStatus::kBlocked) {
    // Stepping off did not help (or nothing free is near): nothing can be planned from
    // here, which says nothing about what is left to explore. Home, and try again from there.
    choice.event = "on a blocked cell: going home";
    return choice;
  }
  if (step.status == ExploreStatus::kDone && !step.out_of_reach.empty())
    if (std::optional<GoalChoice> look = lookAtBlockage(now, odometry, maps, planning, step))
      return std::move(*look);
  const bool idle = travelled < config_.min_sortie_m;
  if (!idle) idle_sorties_ = 0;  // this sortie got somewhere: the row of idle ones is broken
  if (config_.retry_frontiers && step.status == ExploreStatus::kDone && step.failed_left > 0 &&
      config_.max_sorties > 1 && (!idle || idle_sorties_ + 1 < MissionConfig::kMaxIdleSorties)) {
    // Frontiers are left that this sortie could not reach (their goals failed, or have no
    // way to them in this map). After an import the map is another: home to share, and try
    // them again from there, unless sorties from the start keep finding none within reach.
    if (idle) ++idle_sorties_;
    choice.event = "no reachable frontier for now: " + step.reason;
    return choice;
  }
  if (step.status != ExploreStatus::kGoal) {
    exploration_complete_ = true;
    choice.event = complete_reason_ = "exploration complete: " + step.reason;
    return choice;
  }
  if (config_.max_sorties > 1 && step.claim_factor < config_.claimed_return_factor &&
      travelled >= config_.min_sortie_m) {
    // What is left is near where teammates explore: share this part now.
    ++early_returns_;
    choice.event = "own part explored: the frontiers left are teammates'";
    return choice;
  }
  choice.kind = GoalChoice::Kind::kGoal;
  choice.path = step.plan.path;
  by_map_ = false;
  if (maps.memory().hasRecentHits()) {
    const PlanningMap seen_now = maps();
    if (!pathStillValid(choice.path, seen_now)) {
      const PlanResult around = planner_.plan(seen_now, odometry, step.frontier.goal);
      if (around.solved())
        choice.path = around.path;
      else
        by_map_ = true;  // what was just seen cuts every way: the map's (see recheck)
    }
  }
  goal_ = step.frontier.goal;
  has_goal_ = true;
  looking_ = false;
  goal_wait_ = 0.0;
  goal_deadline_ = now + config_.goal_timeout_factor *
                             (choice.path.length() / config_.route.linear_speed + 10.0);
  last_check_ = now;
  // Arriving, face the frontier: the robot would face the way it came, often not the
  // frontier's (a corridor's mouth passed at its side), and a frontier not seen from its goal
  // is not gone to again.
  goal_face_.reset();
  const Eigen::Vector2d to_frontier = step.frontier.centroid - goal_;
  if (to_frontier.norm() > maps.map().limits().resolution) {
    goal_face_ = std::atan2(to_frontier.y(), to_frontier.x());
    goal_deadline_ += config_.goal_timeout_factor * M_PI / config_.route.angular_speed;
  }
  choice.route = route(choice.path, odometry);
  choice.event =
      "to frontier at (" + std::to_string(goal_.x()) + ", " + std::to_string(goal_.y()) + ")";
  return choice;
}

std::optional<GoalChoice> ExplorationGoals::lookAtBlockage(double now, const Pose2& odometry,
                                                           const PlanningMaps& maps,
                                                           const PlanningMap& planning,
                                                           const ExploreStep& step) {
  // The grid turns a cell held at its clamp (1000) free after 27 rays through it (-40 each,
  // to below -60): nine seconds of frames at the paper's 3 Hz, and a second more.
  constexpr double kLookWait = 10.0;
  constexpr int kTries = 3;  // blockages whose look-from place has no path, skipped
  for (int tries = 0; tries < kTries; ++tries) {
    const std::optional<BlockageLook> look =
        findBlockageLook(maps.map(), planning, odometry.translation(), step.out_of_reach, looked_,
                         config_.frontiers.blacklist_radius);
    if (!look) return std::nullopt;
    looked_.push_back(look->at);  // once, whatever comes of it
    PlanResult plan = planner_.plan(planning, odometry, look->from);
    if (!plan.solved()) continue;
    GoalChoice choice;
    choice.kind = GoalChoice::Kind::kGoal;
    choice.path = std::move(plan.path);
    goal_ = look->from;
    has_goal_ = true;
    looking_ = true;
    by_map_ = false;
    goal_face_ = look->heading;
    goal_wait_ = kLookWait;
    goal_deadline_ =
        now +
        config_.goal_timeout_factor * (choice.path.length() / config_.route.linear_speed + 10.0 +
                                       M_PI / config_.route.angular_speed) +
        kLookWait;
    last_check_ = now;
    choice.route = route(choice.path, odometry);
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "to look again at what closes the way to the frontier at (%.1f, %.1f): "
                  "(%.1f, %.1f), from (%.1f, %.1f)",
                  look->frontier.x(), look->frontier.y(), look->at.x(), look->at.y(),
                  look->from.x(), look->from.y());
    choice.event = buf;
    return choice;
  }
  return std::nullopt;
}

std::vector<Waypoint> ExplorationGoals::route(const PlannedPath& path,
                                              const Pose2& odometry) const {
  std::vector<Waypoint> route = routeAlong(path.waypoints);
  if (goal_face_) {
    if (route.empty()) route.push_back({odometry.translation(), false, 0.0, 0.0});
    route.back().face = goal_face_;
    route.back().face_within = config_.route.heading_tolerance;  // a look, not a home-base look
    route.back().wait = goal_wait_;
  }
  return route;
}

std::optional<PlannedPath> ExplorationGoals::pathAround(const PlanningMaps& maps,
                                                        const Pose2& odometry) {
  const PlanResult around = planner_.plan(maps(), odometry, goal_);
  if (!around.solved()) return std::nullopt;
  by_map_ = false;
  return around.path;
}

bool ExplorationGoals::checkDue(double now, bool seen_on_way) {
  if (!(has_goal_ && (seen_on_way || now - last_check_ >= config_.replan_period_s))) return false;
  last_check_ = now;
  return true;
}

GoalCheck ExplorationGoals::recheck(const PlanningMaps& maps, const PlannedPath& path,
                                    const Pose2& odometry, size_t next) {
  GoalCheck check;
  // The map grew under the path: go on if it is still free, else plan anew.
  const PathPlanner::Replan r = planner_.replanIfBlocked(maps(), path, odometry, next);
  if (!r.replanned) return check;
  by_map_ = false;
  if (r.result.solved()) {
    check.kind = GoalCheck::Kind::kReplanned;
    check.path = r.result.path;
    check.event = "path blocked: replanned";
  } else if (maps.memory().hasRecentHits() && r.result.status == PlanStatus::kGoalInvalid &&
             maps({.recent = false}).freeAt(goal_)) {
    if (looking_) {
      // What the cameras have just seen by the look's place is what the look came to see:
      // stand at the nearest place still free, facing the blockage.
      const PlanningMap seen_now = maps();
      if (const std::optional<Eigen::Vector2d> nearer =
              nearestFreeCell(seen_now, goal_, config_.escape_radius)) {
        PlanResult plan = planner_.plan(seen_now, odometry, *nearer);
        if (plan.solved()) {
          goal_ = *nearer;
          const Eigen::Vector2d& at = looked_.back();
          goal_face_ = std::atan2(at.y() - goal_.y(), at.x() - goal_.x());
          check.kind = GoalCheck::Kind::kReplanned;
          check.path = std::move(plan.path);
          check.event = "the look's place taken by what was just seen: looking from nearby";
          return check;
        }
      }
    }
    // The goal stands by what the cameras have just seen: its frontier is seen.
    seen();
    check.kind = GoalCheck::Kind::kTakenAsSeen;
    check.event = "goal by what was just seen: taken as seen";
  } else if (std::optional<PlannedPath> by_map =
                 maps.memory().hasRecentHits()
                     ? pathByMap(maps({.recent = false}), path, odometry, next)
                     : std::nullopt) {
    // Only what the cameras have just seen closes the way; the map, from every view so far,
    // has one. A person passing moves on, and what a doorway seen from the side shows in it
    // (its edge smeared into the opening) goes as the view changes: on by the map, stopping
    // short of what was just seen ahead while it is remembered (MissionAgent::explore).
    by_map_ = true;
    check.kind = GoalCheck::Kind::kReplanned;
    check.path = std::move(*by_map);
    check.event = "way closed by what was just seen: going on by the map";
  } else {
    giveUp();
    check.kind = GoalCheck::Kind::kGivenUp;
    check.event = "path blocked, no new one: goal given up";
  }
  return check;
}

std::optional<PlannedPath> ExplorationGoals::pathByMap(const PlanningMap& map,
                                                       const PlannedPath& path,
                                                       const Pose2& odometry, size_t next) const {
  PathPlanner::Replan r = planner_.replanIfBlocked(map, path, odometry, next);
  if (!r.result.solved()) return std::nullopt;
  return std::move(r.result.path);
}

void ExplorationGoals::reached() {
  by_map_ = false;
  ++goals_reached_;
  if (has_goal_) seen();
  looking_ = false;
}

void ExplorationGoals::giveUp() {
  by_map_ = false;
  if (has_goal_ && !looking_) explorer_.blacklist(goal_);
  looking_ = false;
  ++goals_failed_;
}

void ExplorationGoals::seen() {
  if (looking_) return;  // a place to look from, no frontier's goal
  // The frontier is seen from there or never will be. With retry_frontiers, reached goals
  // are remembered for good (what the robot did not see from there it will not); else the
  // goal is blacklisted for the sortie like a failed one.
  if (config_.retry_frontiers)
    explorer_.markReached(goal_);
  else
    explorer_.blacklist(goal_);
}

void ExplorationGoals::startSortie() {
  claims_.clear();
  explorer_.clearBlacklist();
  looking_ = false;
  has_goal_ = false;
  by_map_ = false;
}

}  // namespace coopmap
