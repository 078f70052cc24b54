#include "core/agent/mission.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/planning/path_planner.h"

namespace coopmap {

namespace {

// Homes nearer than this (m) are the same: no fix moved it.
constexpr double kSameHome = 0.01;

}  // namespace

const char* toString(MissionPhase p) {
  switch (p) {
    case MissionPhase::kLookAtHome:
      return "look at home";
    case MissionPhase::kAtStart:
      return "at start";
    case MissionPhase::kExplore:
      return "explore";
    case MissionPhase::kReturn:
      return "return";
    case MissionPhase::kLookAgain:
      return "look at home again";
    case MissionPhase::kAtHome:
      return "at home";
    case MissionPhase::kDone:
      return "done";
  }
  return "?";
}

MissionAgent::MissionAgent(const Pose2& home, const MissionConfig& config)
    : config_(config),
      safety_(config),
      memory_(config),
      goals_(config),
      homing_(config, home),
      team_(config),
      home_(home) {
  config_.validate();
}

void MissionAgent::startFrom(const Pose2& home, double now) {
  if (phase_ == MissionPhase::kLookAtHome) {  // placed beforehand: explore after the look
    placed_home_ = home;
    return;
  }
  if (phase_ != MissionPhase::kAtStart) return;
  home_ = home;
  homing_.setTarget(home);
  phase_ = MissionPhase::kExplore;
  sortie_start_ = now;
  travelled_ = 0.0;
  memory_.clear();  // what was kept in the odometry frame is elsewhere in the map frame
  pose_jumped_ = true;
  goals_.drop();
  follower_.reset();
  last_event_ = "exploring";
}

void MissionAgent::moveHome(const Pose2& home) {
  if (phase_ != MissionPhase::kAtHome) return;
  home_ = home;
  homing_.setTarget(home);
}

void MissionAgent::lookFrom(const Waypoint& look) {
  if (phase_ != MissionPhase::kAtStart) return;
  phase_ = MissionPhase::kLookAtHome;
  pose_jumped_ = true;  // the poses given are the map frame's from now on
  approach_look_ = look;
  startRoute({look});
  last_event_ = "driving nearer to the home base to look again";
}

void MissionAgent::lookAgainAtStart() {
  if (phase_ != MissionPhase::kAtStart) return;
  phase_ = MissionPhase::kLookAtHome;
  startRoute({{home_.translation(), true, config_.look_turn_rate, 0.0}});
  last_event_ = "no home base found from the start: looking again";
}

void MissionAgent::continueAfterFix(double now) {
  if (phase_ != MissionPhase::kAtHome) return;
  if (goals_.explorationComplete() || sortie_ >= config_.max_sorties) {
    phase_ = MissionPhase::kDone;
    last_event_ = goals_.explorationComplete() ? goals_.completeReason()
                                               : "done: " + std::to_string(sortie_) + " sorties";
    return;
  }
  ++sortie_;
  looked_from_here_ = false;
  homing_.startSortie(home_);
  phase_ = MissionPhase::kExplore;
  sortie_start_ = now;
  travelled_ = 0.0;
  safety_.startSortie();
  memory_.startSortie();  // the estimate's frame changes with the fix
  goals_.startSortie();   // the shared map imported, the frame changed
  pose_jumped_ = true;
  follower_.reset();
  last_event_ = "sortie " + std::to_string(sortie_);
}

void MissionAgent::returnAgain(const Pose2& home) {
  if (phase_ != MissionPhase::kAtHome) return;
  if (looked_from_here_ &&
      (home.translation() - homing_.target().translation()).norm() < kSameHome) {
    lookFromHere(last_pose_, "home blocked: looking again from here");
    return;
  }
  homing_.returnTo(home);
  phase_ = MissionPhase::kReturn;
  pose_jumped_ = true;
  follower_.reset();
  last_event_ = "driving to the home pose by the fix, to look again";
}

void MissionAgent::finish(const std::string& reason, bool position_known) {
  phase_ = MissionPhase::kDone;
  lost_ = !position_known;
  follower_.reset();
  goals_.drop();
  last_event_ = reason;
}

void MissionAgent::setTeammates(std::vector<Eigen::Vector2d> positions, bool priority) {
  team_.set(std::move(positions), priority);
}

void MissionAgent::setTeammateGoals(const std::vector<Eigen::Vector2d>& goals) {
  goals_.claim(goals);
}

std::optional<Eigen::Vector2d> MissionAgent::explorationGoal() const {
  if (phase_ == MissionPhase::kExplore && goals_.hasGoal()) return goals_.goal();
  return std::nullopt;
}

MotionCommand MissionAgent::update(double now, const Pose2& odometry, const OccupancyGrid& map,
                                   const RadialMap* latest, bool bumped,
                                   std::optional<double> bump_bearing) {
  team_.track(now);
  return safety_.limitSpeedUp(decide(now, odometry, map, latest, bumped, bump_bearing), now);
}

MotionCommand MissionAgent::decide(double now, const Pose2& odometry, const OccupancyGrid& map,
                                   const RadialMap* latest, bool bumped,
                                   std::optional<double> bump_bearing) {
  if (start_time_ < 0.0) {  // the first update: look at the home base from the start
    start_time_ = sortie_start_ = now;
    last_pose_ = odometry;
    startRoute({{home_.translation(), true, config_.look_turn_rate, config_.look_wait_s}});
  }
  if (!pose_jumped_) travelled_ += std::hypot(odometry.x - last_pose_.x, odometry.y - last_pose_.y);
  pose_jumped_ = false;
  last_pose_ = odometry;

  // What the robot has driven over, and what its cameras and bumpers find, come first.
  memory_.markVisited(map, odometry);
  const size_t fresh = latest ? memory_.rememberHits(now, odometry, *latest) : 0;
  if (latest) safety_.see(*latest);
  if (std::optional<MotionCommand> cmd = afterBump(now, odometry, map, bumped, bump_bearing))
    return *cmd;
  // Then teammates in the way; then the phase's own business.
  if (std::optional<MotionCommand> cmd = giveWay(now, odometry, map)) return *cmd;
  switch (phase_) {
    case MissionPhase::kLookAtHome:
      return lookAtHome(now, odometry, latest);
    case MissionPhase::kExplore:
      return explore(now, odometry, map, latest, fresh);
    case MissionPhase::kReturn:
      return returnHome(now, odometry, map, latest, fresh);
    case MissionPhase::kLookAgain:
      return lookAgain(now, odometry);
    case MissionPhase::kAtStart:
    case MissionPhase::kAtHome:
    case MissionPhase::kDone:
      break;
  }
  return last_command_ = MotionCommand::stop();
}

std::optional<MotionCommand> MissionAgent::afterBump(double now, const Pose2& odometry,
                                                     const OccupancyGrid& map, bool bumped,
                                                     std::optional<double> bump_bearing) {
  // Touching something: back off, give the goal up, plan anew.
  if (safety_.backingOff(now)) return last_command_ = safety_.backoffCommand();
  const bool moving = phase_ == MissionPhase::kExplore || phase_ == MissionPhase::kReturn;
  if (bumped && moving && safety_.canBackOff()) {
    if (const std::optional<double> at = safety_.backOff(now, bump_bearing, last_command_.linear))
      memory_.addBump(odometry, *at);
    if (phase_ == MissionPhase::kExplore) {
      goals_.giveUp();
      follower_.reset();
    }
    last_event_ = "bumped: backing off";
    return last_command_ = safety_.backoffCommand();
  }
  if (!safety_.backOffDone(now)) return std::nullopt;
  if (safety_.sortieBumps() >= config_.max_sortie_bumps) {
    // Wheels that push against something slip: the odometry no longer says where the robot
    // is, and a look at "home" from wherever it is could give a wrong fix. Stay put.
    finish("stopped: bumped " + std::to_string(safety_.sortieBumps()) +
               " times in this sortie, the odometry cannot be trusted",
           false);
    return last_command_ = MotionCommand::stop();
  }
  if (phase_ == MissionPhase::kReturn) {
    if (homing_.blockedNearHome(odometry)) {
      // Near home but the way is blocked (by what drift hides from the map, or a
      // teammate): look at the home base from here; a fix will bring it home.
      lookFromHere(odometry, "home blocked: looking from here");
      return last_command_ = MotionCommand::stop();
    }
    goHome(now, odometry, map);
  }
  return std::nullopt;
}

std::optional<MotionCommand> MissionAgent::giveWay(double now, const Pose2& odometry,
                                                   const OccupancyGrid& map) {
  const bool moving = phase_ == MissionPhase::kExplore || phase_ == MissionPhase::kReturn;
  const bool driving = moving && follower_ && last_command_.linear > 0.0;
  const std::vector<Eigen::Vector2d> way = wayAhead(odometry);
  // A teammate in or at the passage ahead (a door): wait until it is through and away.
  switch (team_.passageWait(now, odometry, way, map, driving)) {
    case TeamWait::kNewWait:
      last_event_ = "teammate at the passage ahead: waiting";
      return MotionCommand::stop();
    case TeamWait::kWaiting:
      return MotionCommand::stop();
    case TeamWait::kNone:
    case TeamWait::kWaitOver:
      break;
  }
  // A teammate ahead: stop and wait (the last command kept: it is checked again); after a
  // while plan around it.
  switch (team_.teammateWait(now, odometry, way, last_command_.linear, driving)) {
    case TeamWait::kNewWait:
      last_event_ = "teammate ahead: waiting";
      return MotionCommand::stop();
    case TeamWait::kWaiting:
      return MotionCommand::stop();
    case TeamWait::kWaitOver:
      break;
    case TeamWait::kNone:
      return std::nullopt;
  }
  follower_.reset();
  if (phase_ == MissionPhase::kReturn && homing_.nearHome(odometry)) {
    // Near home and a teammate still in the way after the wait (one parked at its own home
    // beside this one's will not move): look at the home base from here, as after bumps
    // near home; a fix will bring it home.
    lookFromHere(odometry, "home blocked by a teammate: looking from here");
    return last_command_ = MotionCommand::stop();
  }
  last_event_ = "teammate ahead: planning around it";
  if (phase_ == MissionPhase::kReturn) {
    goHome(now, odometry, map);
  } else if (goals_.hasGoal()) {
    if (std::optional<PlannedPath> around = goals_.pathAround(planningMaps(map), odometry))
      followToGoal(std::move(*around), odometry);
    else
      goals_.drop();  // not given up: the way is only blocked for now
  }
  return last_command_ = MotionCommand::stop();
}

MotionCommand MissionAgent::lookAtHome(double now, const Pose2& odometry, const RadialMap* latest) {
  // Driving nearer to look again, never into what the cameras see ahead (a teammate at
  // its start between this robot and the home base): the look is taken from here.
  if (approach_look_ && safety_.mustStop(latest, last_command_.linear)) {
    Waypoint here = *approach_look_;
    here.position = odometry.translation();
    approach_look_.reset();
    startRoute({here});
    last_event_ = "obstacle ahead: looking at the home base from here";
    return last_command_ = MotionCommand::stop();
  }
  const MotionCommand cmd = follower_->update(odometry, now);
  if (!follower_->done()) return last_command_ = cmd;
  approach_look_.reset();
  follower_.reset();
  if (placed_home_) {  // placed beforehand, in the frame it works in: explore now
    home_ = *placed_home_;
    homing_.setTarget(*placed_home_);
    phase_ = MissionPhase::kExplore;
    last_event_ = "exploring";
  } else {
    phase_ = MissionPhase::kAtStart;
    last_event_ = "looked at the home base from the start";
  }
  return MotionCommand::stop();
}

MotionCommand MissionAgent::explore(double now, const Pose2& odometry, const OccupancyGrid& map,
                                    const RadialMap* latest, size_t fresh) {
  const double budget =
      sortie_ == 1 && config_.first_budget_m > 0.0 ? config_.first_budget_m : config_.budget_m;
  if (travelled_ >= budget || now - sortie_start_ >= config_.budget_s) {
    last_event_ = "budget spent";
    goHome(now, odometry, map);
    return MotionCommand::stop();
  }
  // On the map's way through what was just seen (ExplorationGoals::byMap): what was seen
  // ahead stops the robot while it is remembered, though the cameras no longer show it (a
  // textureless wall seen only where the floor ends before it).
  const bool seen_ahead =
      goals_.byMap() && last_command_.linear > 0.0 &&
      memory_.recentHitAhead(odometry, config_.safety_distance, config_.safety_half_angle);
  if (follower_ && (safety_.mustStop(latest, last_command_.linear) || seen_ahead)) {
    // Stop; the obstacle is in the map now, so plan to the same goal around it, and give
    // the goal up only when there is no way.
    follower_.reset();
    last_event_ = "obstacle ahead: stopped";
    if (goals_.hasGoal()) {
      if (std::optional<PlannedPath> around = goals_.pathAround(planningMaps(map), odometry)) {
        followToGoal(std::move(*around), odometry);
        last_event_ = "obstacle ahead: replanned around it";
      } else {
        goals_.giveUp();
        goals_.drop();
      }
    }
    return last_command_ = MotionCommand::stop();
  }
  if (follower_ && goals_.overdue(now)) {
    goals_.giveUp();
    follower_.reset();
    last_event_ = "goal not reached in time: given up";
  }
  if (follower_ && follower_->done()) {
    // Reached: the frontier is seen from here or never will be; do not come back.
    goals_.reached();
    follower_.reset();
  }
  // Something just seen on the way: check the path now, not at the next period.
  const bool seen_on_way = follower_ && memory_.freshHitNear(wayAhead(odometry), fresh);
  if (follower_ && path_.waypoints.size() >= 2 && goals_.checkDue(now, seen_on_way)) {
    const size_t next = std::min(follower_->nextWaypoint() + 1, path_.waypoints.size() - 1);
    GoalCheck check = goals_.recheck(planningMaps(map), path_, odometry, next);
    switch (check.kind) {
      case GoalCheck::Kind::kClear:
        break;
      case GoalCheck::Kind::kReplanned:
        followToGoal(std::move(check.path), odometry);
        last_event_ = check.event;
        break;
      case GoalCheck::Kind::kTakenAsSeen:
      case GoalCheck::Kind::kGivenUp:
        follower_.reset();
        last_event_ = check.event;
        break;
    }
  }
  if (!follower_) {
    chooseGoal(now, odometry, map);
    return last_command_ = MotionCommand::stop();
  }
  return last_command_ = safety_.slowed(follower_->update(odometry, now));
}

MotionCommand MissionAgent::returnHome(double now, const Pose2& odometry, const OccupancyGrid& map,
                                       const RadialMap* latest, size_t fresh) {
  if (homing_.planDue(now)) {
    goHome(now, odometry, map);
    return last_command_ = MotionCommand::stop();
  }
  if (!follower_) return last_command_ = MotionCommand::stop();  // waiting to plan again
  if (safety_.mustStop(latest, last_command_.linear)) {
    goHome(now, odometry, map);  // around whatever is in the way
    return last_command_ = MotionCommand::stop();
  }
  const std::vector<Eigen::Vector2d> way = wayAhead(odometry);
  if (memory_.freshHitNear(way, fresh) &&
      firstBlockedSegment(way, planningMaps(map)(homing_.wayMap()))) {
    last_event_ = "way home blocked: replanned";
    goHome(now, odometry, map);
    return last_command_ = MotionCommand::stop();
  }
  if (!follower_->done()) return last_command_ = safety_.slowed(follower_->update(odometry, now));
  if (homing_.endsShort()) {  // as near home as the map went: the map has grown since
    goHome(now, odometry, map);
    return last_command_ = MotionCommand::stop();
  }
  phase_ = MissionPhase::kLookAgain;
  looked_from_here_ = false;
  startRoute({{homing_.target().translation(), true, config_.look_turn_rate, 0.0}});
  return last_command_ = MotionCommand::stop();
}

void MissionAgent::lookFromHere(const Pose2& odometry, const std::string& why) {
  phase_ = MissionPhase::kLookAgain;
  startRoute({{odometry.translation(), true, config_.look_turn_rate, 0.0}});
  looked_from_here_ = true;
  last_event_ = why;
}

MotionCommand MissionAgent::lookAgain(double now, const Pose2& odometry) {
  const MotionCommand cmd = follower_->update(odometry, now);
  if (!follower_->done()) return last_command_ = cmd;
  phase_ = config_.max_sorties > 1 ? MissionPhase::kAtHome : MissionPhase::kDone;
  follower_.reset();
  return last_command_ = MotionCommand::stop();
}

void MissionAgent::startRoute(std::vector<Waypoint> route) {
  follower_ = std::make_unique<RouteFollower>(std::move(route), config_.route);
  homing_.routeStarted();  // a new route ends any wait for a way home
}

void MissionAgent::chooseGoal(double now, const Pose2& odometry, const OccupancyGrid& map) {
  GoalChoice choice = goals_.choose(now, odometry, planningMaps(map), travelled_);
  last_event_ = choice.event;
  switch (choice.kind) {
    case GoalChoice::Kind::kStepOff:
      startRoute(std::move(choice.route));
      break;
    case GoalChoice::Kind::kGoHome:
      goHome(now, odometry, map);
      break;
    case GoalChoice::Kind::kGoal:
      path_ = std::move(choice.path);
      startRoute(std::move(choice.route));
      break;
  }
}

void MissionAgent::followToGoal(PlannedPath path, const Pose2& odometry) {
  path_ = std::move(path);
  startRoute(goals_.route(path_, odometry));
}

void MissionAgent::goHome(double now, const Pose2& odometry, const OccupancyGrid& map) {
  phase_ = MissionPhase::kReturn;
  goals_.drop();
  HomeWay way = homing_.plan(now, odometry, planningMaps(map));
  path_ = std::move(way.path);
  if (way.route)
    startRoute(std::move(*way.route));
  else
    follower_.reset();
  if (!way.event.empty()) last_event_ = way.event;
}

PlanningMaps MissionAgent::planningMaps(const OccupancyGrid& map) const {
  return PlanningMaps(map, memory_, last_pose_.translation(), team_.positions());
}

std::vector<Eigen::Vector2d> MissionAgent::wayAhead(const Pose2& pose) const {
  std::vector<Eigen::Vector2d> way{pose.translation()};
  if (follower_ && path_.waypoints.size() >= 2) {
    for (size_t k = std::min(follower_->nextWaypoint() + 1, path_.waypoints.size() - 1);
         k < path_.waypoints.size(); ++k)
      way.push_back(path_.waypoints[k]);
  } else {
    way.push_back(homing_.target().translation());
  }
  return way;
}

}  // namespace coopmap
