#include "core/agent/mission.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace coopmap {

namespace {

std::vector<Waypoint> routeOf(const std::vector<Eigen::Vector2d>& waypoints) {
  std::vector<Waypoint> route;
  for (size_t i = 1; i < waypoints.size(); ++i) route.push_back({waypoints[i], false, 0.0, 0.0});
  return route;
}

}  // namespace

void MissionConfig::validate() const {
  auto positive = [](const char* field, double v) {
    if (!(v > 0.0))
      throw std::invalid_argument(std::string("mission config: field '") + field +
                                  "': expected a positive number, got " + std::to_string(v));
  };
  positive("budget_m", budget_m);
  positive("budget_s", budget_s);
  positive("replan_period_s", replan_period_s);
  positive("safety_distance", safety_distance);
  positive("safety_half_angle", safety_half_angle);
  positive("look_turn_rate", look_turn_rate);
  positive("goal_timeout_factor", goal_timeout_factor);
  positive("backoff_s", backoff_s);
  positive("escape_radius", escape_radius);
  positive("team_distance", team_distance);
  positive("team_half_angle", team_half_angle);
  positive("team_wait_s", team_wait_s);
  positive("team_radius", team_radius);
  positive("team_close", team_close);
  positive("look_from_m", look_from_m);
  positive("bump_radius", bump_radius);
  positive("max_home_detour", max_home_detour);
  positive("home_retry_s", home_retry_s);
  // field, whether its value is good, what is expected, the value
  auto require = [](const char* field, bool ok, const char* expected, double v) {
    if (!ok)
      throw std::invalid_argument(std::string("mission config: field '") + field + "': expected " +
                                  expected + ", got " + std::to_string(v));
  };
  require("max_linear_accel", max_linear_accel >= 0.0, "a number >= 0 (0: the base's)",
          max_linear_accel);
  require("slow_distance", slow_distance >= 0.0, "a number >= 0 (0: off)", slow_distance);
  require("slow_fraction", slow_fraction > 0.0 && slow_fraction <= 1.0, "a number in (0, 1]",
          slow_fraction);
  require("recent_hits_s", recent_hits_s >= 0.0, "a number >= 0 (0: off)", recent_hits_s);
  positive("recent_hits_range", recent_hits_range);
  require("recent_hits_support", recent_hits_support >= 1, "at least 1", recent_hits_support);
  require("first_budget_m", first_budget_m >= 0.0, "a number >= 0 (0: budget_m)", first_budget_m);
  require("bump_width", bump_width >= 0.0, "a number >= 0", bump_width);
  require("passage_width", passage_width >= 0.0, "a number >= 0 (0: off)", passage_width);
  positive("passage_lookahead", passage_lookahead);
  positive("passage_radius", passage_radius);
  positive("passage_wait_s", passage_wait_s);
  require("visited_radius", visited_radius >= 0.0, "a number >= 0 (0: the robot's radius)",
          visited_radius);
  require("claimed_return_factor", claimed_return_factor >= 0.0 && claimed_return_factor <= 1.0,
          "a number in [0, 1]", claimed_return_factor);
  require("min_sortie_m", min_sortie_m >= 0.0, "a number >= 0", min_sortie_m);
  require("look_wait_s", look_wait_s >= 0.0, "a number >= 0", look_wait_s);
  require("trail_after_waits", trail_after_waits >= 0, "a number >= 0 (0: never)",
          trail_after_waits);
  auto atLeastOne = [](const char* field, int v) {
    if (v < 1)
      throw std::invalid_argument(std::string("mission config: field '") + field +
                                  "': expected at least 1, got " + std::to_string(v));
  };
  atLeastOne("firm_log_odds", firm_log_odds);
  atLeastOne("max_sortie_bumps", max_sortie_bumps);
  atLeastOne("max_return_bumps", max_return_bumps);
  atLeastOne("max_sorties", max_sorties);
  frontiers.validate();
  planner.validate();
  planning.validate();
  route.validate();
}

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
    : home_(home),
      target_(home),
      config_(config),
      explorer_(config.frontiers, config.planner),
      planner_(config.planner) {
  config_.validate();
}

void MissionAgent::startRoute(std::vector<Waypoint> route, double) {
  follower_ = std::make_unique<RouteFollower>(std::move(route), config_.route);
  home_retry_at_ = -1.0;  // a new route ends any wait
}

MotionCommand MissionAgent::slowed(MotionCommand cmd) const {
  if (config_.slow_distance <= config_.safety_distance || cmd.linear <= 0.0) return cmd;
  const double f = std::clamp((nearest_ahead_ - config_.safety_distance) /
                                  (config_.slow_distance - config_.safety_distance),
                              config_.slow_fraction, 1.0);
  cmd.linear = std::min(cmd.linear, f * config_.route.linear_speed);
  return cmd;
}

bool MissionAgent::obstacleAhead(const RadialMap& scan) const {
  for (const RadialReading& r : scan.readings)
    if (r.kind == RadialKind::kHit && r.range < config_.safety_distance &&
        std::abs(r.bearing) < config_.safety_half_angle)
      return true;
  return false;
}

void MissionAgent::goalSeen() {
  // The frontier is seen from there or never will be. With retry_frontiers, reached goals
  // are remembered for good (what the robot did not see from there it will not); else the
  // goal is blacklisted for the sortie like a failed one.
  if (config_.retry_frontiers)
    explorer_.markReached(goal_);
  else
    explorer_.blacklist(goal_);
}

void MissionAgent::chooseGoal(double now, const Pose2& odometry, const OccupancyGrid& map) {
  // Goals by the map: what was just seen (a person, a teammate passing) is no reason to end
  // the exploration or give a frontier up. The path to the goal goes round it, if it can.
  const PlanningMap planning = planningMap(map, false, false);
  if (!planning.freeAt(odometry.translation())) {
    // Something seen too close (a stereo mismatch, a person passing) leaves the robot on a
    // cell the planner will not start from: step to the nearest free one first.
    const std::optional<Eigen::Vector2d> to = nearestFreeCell(planning, odometry);
    if (to && !escaping_) {
      escaping_ = true;
      has_goal_ = false;
      startRoute({{*to, false, 0.0, 0.0}}, now);
      last_event_ = "stepping off a blocked cell";
      return;
    }
  }
  escaping_ = false;
  const ExploreStep step = explorer_.next(map, planning, odometry, claims_);
  if (step.status == ExploreStatus::kBlocked) {
    // Stepping off did not help (or nothing free is near): nothing can be planned from
    // here, which says nothing about what is left to explore. Home, and try again from there.
    last_event_ = "on a blocked cell: going home";
    goHome(now, odometry, map);
    return;
  }
  const bool idle = travelled_ < config_.min_sortie_m;
  if (!idle) idle_sorties_ = 0;  // this sortie got somewhere: the row of idle ones is broken
  if (config_.retry_frontiers && step.status == ExploreStatus::kDone && step.failed_left > 0 &&
      config_.max_sorties > 1 && (!idle || idle_sorties_ + 1 < MissionConfig::kMaxIdleSorties)) {
    // Frontiers are left that this sortie could not reach (their goals failed, or have no
    // way to them in this map). After an import the map is another: home to share, and try
    // them again from there, unless sorties from the start keep finding none within reach.
    if (idle) ++idle_sorties_;
    last_event_ = "no reachable frontier for now: " + step.reason;
    goHome(now, odometry, map);
    return;
  }
  if (step.status != ExploreStatus::kGoal) {
    exploration_complete_ = true;
    last_event_ = complete_reason_ = "exploration complete: " + step.reason;
    goHome(now, odometry, map);
    return;
  }
  if (config_.max_sorties > 1 && step.claim_factor < config_.claimed_return_factor &&
      travelled_ >= config_.min_sortie_m) {
    // What is left is near where teammates explore: share this part now.
    ++early_returns_;
    last_event_ = "own part explored: the frontiers left are teammates'";
    goHome(now, odometry, map);
    return;
  }
  path_ = step.plan.path;
  if (!recent_.empty()) {
    const PlanningMap seen_now = planningMap(map, false);
    if (!pathStillValid(path_, seen_now)) {
      const PlanResult around = planner_.plan(seen_now, odometry, step.frontier.goal);
      if (around.solved()) path_ = around.path;
    }
  }
  goal_ = step.frontier.goal;
  has_goal_ = true;
  goal_deadline_ =
      now + config_.goal_timeout_factor * (path_.length() / config_.route.linear_speed + 10.0);
  last_check_ = now;
  // Arriving, face the frontier: the robot would face the way it came, often not the
  // frontier's (a corridor's mouth passed at its side), and a frontier not seen from its goal
  // is not gone to again.
  goal_face_.reset();
  const Eigen::Vector2d to_frontier = step.frontier.centroid - goal_;
  if (to_frontier.norm() > map.limits().resolution) {
    goal_face_ = std::atan2(to_frontier.y(), to_frontier.x());
    goal_deadline_ += config_.goal_timeout_factor * M_PI / config_.route.angular_speed;
  }
  std::vector<Waypoint> route = goalRoute(odometry);
  if (step.look_around) {
    // Its frontier was not seen from this goal before: a full circle there shows it.
    if (route.empty()) route.push_back({odometry.translation(), false, 0.0, 0.0});
    route.back().spin = true;
    goal_deadline_ += config_.goal_timeout_factor * 2.0 * M_PI / config_.route.angular_speed;
  }
  startRoute(std::move(route), now);
  last_event_ = std::string(step.look_around ? "to look around again at (" : "to frontier at (") +
                std::to_string(goal_.x()) + ", " + std::to_string(goal_.y()) + ")";
}

std::vector<Waypoint> MissionAgent::goalRoute(const Pose2& odometry) const {
  std::vector<Waypoint> route = routeOf(path_.waypoints);
  if (goal_face_) {
    if (route.empty()) route.push_back({odometry.translation(), false, 0.0, 0.0});
    route.back().face = goal_face_;
    route.back().face_within = config_.route.heading_tolerance;  // a look, not a home-base look
  }
  return route;
}

void MissionAgent::goHome(double now, const Pose2& odometry, const OccupancyGrid& map) {
  phase_ = MissionPhase::kReturn;
  has_goal_ = false;
  plan_home_at_end_ = false;
  home_margin_ = -1.0;
  // On a blocked cell (backed off from a bump into what it has just drawn): step off to the
  // nearest free cell first, and plan from there.
  const PlanningMap planning = planningMap(map, false);
  Pose2 from = odometry;
  const bool step_off = !planning.freeAt(odometry.translation());
  if (step_off)
    if (const std::optional<Eigen::Vector2d> to = nearestFreeCell(planning, odometry))
      from = Pose2(to->x(), to->y(), odometry.theta);
  const Eigen::Vector2d home = target_.translation();
  PlanResult plan = planner_.plan(planning, from, home);
  if (!plan.solved()) {
    PlanResult unknown = planner_.plan(planningMap(map, true), from, home);
    const double straight = (home - from.translation()).norm();
    if (unknown.solved() && unknown.path.length() <= config_.max_home_detour * straight + 2.0) {
      plan = std::move(unknown);
    } else if (const std::optional<Eigen::Vector2d> near = nearestReachable(planning, from, home)) {
      // No short way home: as near to it as the known free space goes, and plan again there.
      plan = planner_.plan(planning, from, *near);
      if (plan.solved()) plan_home_at_end_ = true;
    }
  }
  // No way with the margin: with the least one that keeps the body off every blocked cell.
  const double least = leastMargin(map.limits());
  bool squeezed = false;
  if (!plan.solved() && (home - odometry.translation()).norm() > config_.look_from_m) {
    if (least < config_.planning.margin) {
      const PlanningMap tight = planningMap(map, false, true, least);
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
      home_waits_ >= config_.trail_after_waits && !trail_.cells.empty()) {
    const PlanningMap trail = planningMap(map, false, true, least, true);
    if (trail.freeAt(from.translation())) {
      plan = planner_.plan(trail, from, home);
      on_trail = plan.solved();
    }
  }
  home_on_trail_ = on_trail;
  if (plan.solved()) {
    path_ = plan.path;
    if (step_off) path_.waypoints.insert(path_.waypoints.begin(), odometry.translation());
    startRoute(routeOf(path_.waypoints), now);
    if (squeezed || on_trail) home_margin_ = least;
    if (squeezed) last_event_ = "no way home with the planning margin: going with the least";
    if (on_trail)
      last_event_ = "no way home in the map after " + std::to_string(home_waits_) +
                    " waits: going home on the trail driven out";
    else
      home_waits_ = 0;
  } else if ((home - odometry.translation()).norm() <= config_.look_from_m) {
    path_ = PlannedPath{};
    startRoute({{target_.translation(), false, 0.0, 0.0}}, now);  // straight: nothing better
  } else {
    // No way home in the map now: never straight through what it shows; wait, plan again.
    path_ = PlannedPath{};
    follower_.reset();
    home_retry_at_ = now + config_.home_retry_s;
    ++home_waits_;
    last_event_ = "no way home in the map: waiting to plan again";
  }
}

void MissionAgent::continueAfterFix(double now) {
  if (phase_ != MissionPhase::kAtHome) return;
  if (exploration_complete_ || sortie_ >= config_.max_sorties) {
    phase_ = MissionPhase::kDone;
    last_event_ =
        exploration_complete_ ? complete_reason_ : "done: " + std::to_string(sortie_) + " sorties";
    return;
  }
  ++sortie_;
  target_ = home_;
  return_bumps_ = 0;
  phase_ = MissionPhase::kExplore;
  sortie_start_ = now;
  travelled_ = 0.0;
  sortie_bumps_ = 0;
  bumps_.clear();  // the estimate's frame changes with the fix
  trail_ = GridU8{};
  home_waits_ = 0;
  recent_.clear();
  claims_.clear();             // what teammates posted is in the imported map now
  explorer_.clearBlacklist();  // the goals failed in the old frame, on the old map
  pose_jumped_ = true;
  has_goal_ = false;
  follower_.reset();
  last_event_ = "sortie " + std::to_string(sortie_);
}

void MissionAgent::startFrom(const Pose2& home, double now) {
  if (phase_ == MissionPhase::kLookAtHome) {  // placed beforehand: explore after the look
    placed_home_ = home;
    return;
  }
  if (phase_ != MissionPhase::kAtStart) return;
  home_ = target_ = home;
  phase_ = MissionPhase::kExplore;
  sortie_start_ = now;
  travelled_ = 0.0;
  // What was kept in the odometry frame is elsewhere in the map frame.
  bumps_.clear();
  recent_.clear();
  visited_ = GridU8{};
  trail_ = GridU8{};
  pose_jumped_ = true;
  has_goal_ = false;
  follower_.reset();
  last_event_ = "exploring";
}

void MissionAgent::moveHome(const Pose2& home) {
  if (phase_ != MissionPhase::kAtHome) return;
  home_ = target_ = home;
}

void MissionAgent::lookFrom(const Waypoint& look, double now) {
  if (phase_ != MissionPhase::kAtStart) return;
  phase_ = MissionPhase::kLookAtHome;
  pose_jumped_ = true;  // the poses given are the map frame's from now on
  approach_look_ = look;
  startRoute({look}, now);
  last_event_ = "driving nearer to the home base to look again";
}

void MissionAgent::lookAgainAtStart(double now) {
  if (phase_ != MissionPhase::kAtStart) return;
  phase_ = MissionPhase::kLookAtHome;
  startRoute({{home_.translation(), true, config_.look_turn_rate, 0.0}}, now);
  last_event_ = "no home base found from the start: looking again";
}

void MissionAgent::finish(const std::string& reason, bool position_known) {
  phase_ = MissionPhase::kDone;
  lost_ = !position_known;
  follower_.reset();
  has_goal_ = false;
  last_event_ = reason;
}

std::optional<Eigen::Vector2d> MissionAgent::explorationGoal() const {
  if (phase_ == MissionPhase::kExplore && has_goal_) return goal_;
  return std::nullopt;
}

void MissionAgent::returnAgain(const Pose2& home) {
  if (phase_ != MissionPhase::kAtHome) return;
  target_ = home;
  return_bumps_ = 0;
  phase_ = MissionPhase::kReturn;
  plan_home_ = true;
  pose_jumped_ = true;
  follower_.reset();
  last_event_ = "driving to the home pose by the fix, to look again";
}

MotionCommand MissionAgent::update(double now, const Pose2& odometry, const OccupancyGrid& map,
                                   const RadialMap* latest, bool bumped,
                                   std::optional<double> bump_bearing) {
  trackTeammates(now);
  const MotionCommand decided = decide(now, odometry, map, latest, bumped, bump_bearing);
  const MotionCommand cmd = limitSpeedUp(decided, sent_linear_, config_.max_linear_accel,
                                         sent_at_ < 0.0 ? 0.0 : now - sent_at_);
  sent_linear_ = cmd.kind == MotionCommand::Kind::kVelocity ? cmd.linear : 0.0;
  sent_at_ = now;
  return cmd;
}

MotionCommand MissionAgent::decide(double now, const Pose2& odometry, const OccupancyGrid& map,
                                   const RadialMap* latest, bool bumped,
                                   std::optional<double> bump_bearing) {
  if (start_time_ < 0.0) {
    start_time_ = sortie_start_ = now;
    last_pose_ = odometry;
    startRoute({{home_.translation(), true, config_.look_turn_rate, config_.look_wait_s}}, now);
  }
  if (!pose_jumped_) travelled_ += std::hypot(odometry.x - last_pose_.x, odometry.y - last_pose_.y);
  pose_jumped_ = false;
  last_pose_ = odometry;
  markVisited(map, odometry);
  const size_t fresh =
      latest && config_.recent_hits_s > 0.0 ? rememberHits(now, odometry, *latest) : 0;
  if (latest) {
    nearest_ahead_ = 1e9;
    for (const RadialReading& r : latest->readings)
      if (r.kind == RadialKind::kHit && std::abs(r.bearing) < config_.safety_half_angle)
        nearest_ahead_ = std::min(nearest_ahead_, r.range);
  }
  // Touching something: back off, give the goal up, plan anew.
  if (now < backoff_until_) return last_command_ = MotionCommand{backoff_speed_, 0.0};
  const bool moving = phase_ == MissionPhase::kExplore || phase_ == MissionPhase::kReturn;
  if (bumped && moving && backoff_until_ < 0.0) {
    ++safety_stops_;
    backoff_until_ = now + config_.backoff_s;
    backoff_speed_ = -0.1;
    // The bumper found what the map missed (too low, too thin, or drift put it elsewhere):
    // an obstacle where the robot touched it, in the frame of its estimate like its map.
    std::optional<double> bearing;
    if (config_.bump_away && bump_bearing) {
      bearing = *bump_bearing;
      if (std::cos(*bearing) < 0.0) backoff_speed_ = 0.1;  // touched behind: away is forwards
    } else if (last_command_.linear != 0.0) {
      bearing = last_command_.linear > 0.0 ? 0.0 : M_PI;
    }
    if (bearing) {
      const double edge = config_.planning.robot_radius + 0.5 * config_.bump_radius;
      const Eigen::Vector2d at(std::cos(*bearing), std::sin(*bearing));
      const Eigen::Vector2d across(-at.y(), at.x());
      const int n = static_cast<int>(std::ceil(0.5 * config_.bump_width / config_.bump_radius));
      for (int k = -n; k <= n; ++k) {
        const double s = std::clamp(k * config_.bump_radius, -0.5 * config_.bump_width,
                                    0.5 * config_.bump_width);
        bumps_.push_back(odometry * Eigen::Vector2d(edge * at + s * across));
      }
    }
    if (phase_ == MissionPhase::kExplore) {
      if (has_goal_) explorer_.blacklist(goal_);
      ++goals_failed_;
      follower_.reset();
    }
    last_event_ = "bumped: backing off";
    return last_command_ = MotionCommand{backoff_speed_, 0.0};
  }
  if (backoff_until_ >= 0.0 && now >= backoff_until_) {
    backoff_until_ = -1.0;
    if (++sortie_bumps_ >= config_.max_sortie_bumps) {
      // Wheels that push against something slip: the odometry no longer says where the robot
      // is, and a look at "home" from wherever it is could give a wrong fix. Stay put.
      finish("stopped: bumped " + std::to_string(sortie_bumps_) +
                 " times in this sortie, the odometry cannot be trusted",
             false);
      return last_command_ = MotionCommand::stop();
    }
    if (phase_ == MissionPhase::kReturn) {
      if (++return_bumps_ >= config_.max_return_bumps &&
          (odometry.translation() - target_.translation()).norm() < config_.look_from_m) {
        // Near home but the way is blocked (by what drift hides from the map, or a
        // teammate): look at the home base from here; a fix will bring it home.
        phase_ = MissionPhase::kLookAgain;
        startRoute({{odometry.translation(), true, config_.look_turn_rate, 0.0}}, now);
        last_event_ = "home blocked: looking from here";
        return last_command_ = MotionCommand::stop();
      }
      goHome(now, odometry, map);
    }
  }

  // A teammate in or at the passage ahead (a door): wait until it is through and away.
  if (config_.passage_width > 0.0 && moving && follower_ && last_command_.linear > 0.0 &&
      now >= passage_next_ && passageHeld(odometry, map)) {
    if (passage_wait_since_ < 0.0) {
      passage_wait_since_ = now;
      ++passage_waits_;
      last_event_ = "teammate at the passage ahead: waiting";
    }
    if (now - passage_wait_since_ < config_.passage_wait_s) return MotionCommand::stop();
    passage_next_ = now + config_.passage_wait_s;  // waited long enough: go, for a while
  }
  passage_wait_since_ = -1.0;

  // A teammate ahead: stop and wait; after a while plan around it.
  if (moving && follower_ && last_command_.linear > 0.0 && teammateInTheWay(odometry)) {
    if (team_wait_until_ < 0.0) {
      ++team_stops_;
      team_wait_until_ = now + (priority_ ? 0.25 : 1.0) * config_.team_wait_s;
      last_event_ = "teammate ahead: waiting";
    }
    if (now < team_wait_until_) return MotionCommand::stop();  // last_command_ kept: re-checked
    team_wait_until_ = -1.0;
    follower_.reset();
    last_event_ = "teammate ahead: planning around it";
    if (phase_ == MissionPhase::kReturn) {
      goHome(now, odometry, map);
    } else if (has_goal_) {
      const PlanResult around = planner_.plan(planningMap(map, false), odometry, goal_);
      if (around.solved()) {
        path_ = around.path;
        startRoute(goalRoute(odometry), now);
      } else {
        has_goal_ = false;  // not blacklisted: the way is only blocked for now
      }
    }
    return last_command_ = MotionCommand::stop();
  }
  if (team_wait_until_ >= 0.0 && !teammateInTheWay(odometry)) team_wait_until_ = -1.0;

  switch (phase_) {
    case MissionPhase::kLookAtHome: {
      // Driving nearer to look again, never into what the cameras see ahead (a teammate at
      // its start between this robot and the home base): the look is taken from here.
      if (approach_look_ && last_command_.linear > 0.0 && latest && obstacleAhead(*latest)) {
        ++safety_stops_;
        Waypoint here = *approach_look_;
        here.position = odometry.translation();
        approach_look_.reset();
        startRoute({here}, now);
        last_event_ = "obstacle ahead: looking at the home base from here";
        return last_command_ = MotionCommand::stop();
      }
      const MotionCommand cmd = follower_->update(odometry, now);
      if (!follower_->done()) return last_command_ = cmd;
      approach_look_.reset();
      follower_.reset();
      if (placed_home_) {  // placed beforehand, in the frame it works in: explore now
        home_ = target_ = *placed_home_;
        phase_ = MissionPhase::kExplore;
        last_event_ = "exploring";
      } else {
        phase_ = MissionPhase::kAtStart;
        last_event_ = "looked at the home base from the start";
      }
      return MotionCommand::stop();
    }
    case MissionPhase::kExplore: {
      const double budget =
          sortie_ == 1 && config_.first_budget_m > 0.0 ? config_.first_budget_m : config_.budget_m;
      if (travelled_ >= budget || now - sortie_start_ >= config_.budget_s) {
        last_event_ = "budget spent";
        goHome(now, odometry, map);
        return MotionCommand::stop();
      }
      const bool driving = last_command_.linear > 0.0;
      if (follower_ && latest && driving && obstacleAhead(*latest)) {
        // Stop; the obstacle is in the map now, so plan to the same goal around it, and give
        // the goal up only when there is no way.
        ++safety_stops_;
        follower_.reset();
        last_event_ = "obstacle ahead: stopped";
        if (has_goal_) {
          const PlanResult around = planner_.plan(planningMap(map, false), odometry, goal_);
          if (around.solved()) {
            path_ = around.path;
            startRoute(goalRoute(odometry), now);
            last_event_ = "obstacle ahead: replanned around it";
          } else {
            ++goals_failed_;
            explorer_.blacklist(goal_);
            has_goal_ = false;
          }
        }
        return last_command_ = MotionCommand::stop();
      }
      if (follower_ && has_goal_ && now > goal_deadline_) {
        ++goals_failed_;
        explorer_.blacklist(goal_);
        follower_.reset();
        last_event_ = "goal not reached in time: given up";
      }
      if (follower_ && follower_->done()) {
        // Reached: the frontier is seen from here or never will be; do not come back.
        ++goals_reached_;
        if (has_goal_) goalSeen();
        follower_.reset();
      }
      // Something just seen on the way: check the path now, not at the next period.
      const bool seen_on_way = follower_ && freshHitOnWay(odometry, fresh);
      if (follower_ && has_goal_ && path_.waypoints.size() >= 2 &&
          (seen_on_way || now - last_check_ >= config_.replan_period_s)) {
        // The map grew under the path: go on if it is still free, else plan anew.
        last_check_ = now;
        const PlanningMap planning = planningMap(map, false);
        const size_t next = std::min(follower_->nextWaypoint() + 1, path_.waypoints.size() - 1);
        const PathPlanner::Replan r = planner_.replanIfBlocked(planning, path_, odometry, next);
        if (r.replanned) {
          if (r.result.solved()) {
            path_ = r.result.path;
            startRoute(goalRoute(odometry), now);
            last_event_ = "path blocked: replanned";
          } else if (!recent_.empty() && r.result.status == PlanStatus::kGoalInvalid &&
                     planningMap(map, false, false).freeAt(goal_)) {
            // The goal stands by what the cameras have just seen: its frontier is seen.
            goalSeen();
            follower_.reset();
            last_event_ = "goal by what was just seen: taken as seen";
          } else {
            ++goals_failed_;
            explorer_.blacklist(goal_);
            follower_.reset();
            last_event_ = "path blocked, no new one: goal given up";
          }
        }
      }
      if (!follower_) {
        chooseGoal(now, odometry, map);
        return last_command_ = MotionCommand::stop();
      }
      return last_command_ = slowed(follower_->update(odometry, now));
    }
    case MissionPhase::kReturn: {
      if (plan_home_ || (home_retry_at_ >= 0.0 && now >= home_retry_at_)) {
        plan_home_ = false;
        goHome(now, odometry, map);
        return last_command_ = MotionCommand::stop();
      }
      if (!follower_) return last_command_ = MotionCommand::stop();  // waiting to plan again
      const bool driving = last_command_.linear > 0.0;
      if (latest && driving && obstacleAhead(*latest)) {
        ++safety_stops_;
        goHome(now, odometry, map);  // around whatever is in the way
        return last_command_ = MotionCommand::stop();
      }
      if (freshHitOnWay(odometry, fresh) &&
          firstBlockedSegment(wayAhead(odometry),
                              planningMap(map, false, true, home_margin_, home_on_trail_))) {
        last_event_ = "way home blocked: replanned";
        goHome(now, odometry, map);
        return last_command_ = MotionCommand::stop();
      }
      if (!follower_->done()) return last_command_ = slowed(follower_->update(odometry, now));
      if (plan_home_at_end_) {  // as near home as the map went: the map has grown since
        goHome(now, odometry, map);
        return last_command_ = MotionCommand::stop();
      }
      phase_ = MissionPhase::kLookAgain;
      startRoute({{target_.translation(), true, config_.look_turn_rate, 0.0}}, now);
      return last_command_ = MotionCommand::stop();
    }
    case MissionPhase::kLookAgain: {
      const MotionCommand cmd = follower_->update(odometry, now);
      if (!follower_->done()) return last_command_ = cmd;
      phase_ = config_.max_sorties > 1 ? MissionPhase::kAtHome : MissionPhase::kDone;
      follower_.reset();
      return last_command_ = MotionCommand::stop();
    }
    case MissionPhase::kAtStart:
    case MissionPhase::kAtHome:
    case MissionPhase::kDone:
      break;
  }
  return last_command_ = MotionCommand::stop();
}

}  // namespace coopmap
