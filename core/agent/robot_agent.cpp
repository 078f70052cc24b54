#include "core/agent/robot_agent.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace coopmap {

namespace {

// How far a route's home-base fix may move the robot, per metre of the route (m/m, rad/m): a
// generous bound on drifting odometry (the building's 78 m loop ends metres and tens of
// degrees off; the B-14's heading drifts 0.0055 rad/m).
constexpr double kRouteDriftPerMetre = 0.15;
constexpr double kRouteTurnDriftPerMetre = 0.01;

}  // namespace

const char* toString(AgentSetup::Mode mode) {
  switch (mode) {
    case AgentSetup::Mode::kRoute:
      return "route";
    case AgentSetup::Mode::kExplore:
      return "explore";
    case AgentSetup::Mode::kDriven:
      return "driven";
  }
  return "?";
}

void AgentSetup::validate() const {
  if (name.empty()) throw std::invalid_argument("agent setup: field 'name': expected a name");
  if (!(map.resolution > 0.0) || map.width < 1 || map.height < 1)
    throw std::invalid_argument("agent setup: field 'map': expected a resolution > 0 and a size");
  if (home_base) home_base->validate();
  if (mode == Mode::kRoute && route.empty())
    throw std::invalid_argument("agent setup: field 'route': expected at least one waypoint");
}

RobotAgent::RobotAgent(RobotInterface& robot, const AgentSetup& setup,
                       const AgentSettings& settings, SharedMapService* shared, TeamChannel* team)
    : robot_(robot), setup_(setup), settings_(settings), shared_(shared), team_(team) {
  setup_.validate();
  settings_.validate();
  const RobotDescription& d = robot_.description();
  const AgentSettings& s = settings_;
  MapperConfig mapper;
  mapper.radial.floor_edge_depth = s.floor_edge_depth;
  mapper.radial.beyond_support = s.beyond_support;
  mapper.centred_scans = s.stereo_distance_scale;  // the scale is matched on centred windows
  mapper_ = std::make_unique<Mapper>(d, setup_.map, mapper);
  mapper_->setRobotName(setup_.name);
  sense_period_ = 1.0 / s.sensing_rate;

  CooperationConfig& c = cooperation_config_;
  c.setClosureKinds(s.closures);  // checked by validate()
  c.closure_shape = s.shaped_closures;
  c.closure_alignment.seen_points_only = s.closure_seen_points;
  c.manhattan_sigma_rad = s.manhattan_sigma_deg * M_PI / 180.0;
  c.closure_scans = s.closure_scans;
  // A distance scale calibrated beforehand (neither learnt from the sorties' corrections nor
  // measured by the cameras as the mission goes) is held by each sortie's correction: the
  // home-base fix cannot see it.
  c.correction.fit_distance_scale = s.calibrate_distance_scale || s.stereo_distance_scale;
  c.validate();

  if (setup_.mode == AgentSetup::Mode::kExplore) {
    const bool cooperative = shared_ != nullptr && s.max_sorties > 1 && setup_.home_base;
    MissionConfig m;
    m.planning = PlanningMapConfig::forRobot(d);
    m.planning.margin = s.planning_margin;
    m.planner.seed = setup_.seed;
    m.planner.preferred_margin = s.preferred_margin;
    m.budget_m = s.sortie_budget_m;
    m.budget_s = s.sortie_budget_s;
    m.first_budget_m = cooperative ? s.first_sortie_budget_m : 0.0;
    m.safety_distance = s.safety_distance;
    m.slow_distance = s.slow_distance;
    m.frontiers.fringe_clearance = s.fringe_clearance;
    m.frontiers.doorway_width = s.doorway_width;
    m.retry_frontiers = s.retry_frontiers;
    m.bump_away = s.bump_away;
    m.visited_radius = s.visited_radius;
    m.max_linear_accel = s.max_linear_accel;
    // Turns in place stop as the base can stop them; half its angular acceleration, as a
    // command reaches the base up to a control step late.
    m.route.angular_decel = 0.5 * d.max_angular_accel;
    m.recent_hits_s = s.recent_hits_s;
    m.passage_width = s.passage_width;
    m.max_sorties = cooperative ? s.max_sorties : 1;
    m.validate();
    mission_ = std::make_unique<MissionAgent>(Pose2(), m);
    WallHeadingConfig headings;
    headings.gain = s.wall_heading_gain;
    headings_ = WallHeadingTracker(headings);
    if (cooperative) {
      coop_ = std::make_unique<HomeBaseCooperation>(setup_.name, setup_.home_base->visibleCorners(),
                                                    setup_.home_base->arm_length, shared_, c);
      calibrate_ = s.calibrate_odometry;
      // With the scale from stereo, the sorties' corrections do not also move it.
      stereo_scale_ = s.stereo_distance_scale;
      calibration_ = OdometryCalibration(s.calibrate_distance_scale && !s.stereo_distance_scale);
      calibration_.setDistanceScale(s.odometry_distance_scale);
      sortie_scale_ = calibration_.bias().distance_scale;
    }
  } else if (setup_.mode == AgentSetup::Mode::kRoute) {
    const MissionConfig look;  // the mission's look: wait facing, then a slow full turn
    look_ = std::make_unique<RouteFollower>(
        std::vector<Waypoint>{{{0.0, 0.0}, true, look.look_turn_rate, look.look_wait_s}},
        RouteConfig{});
    if (shared_ && setup_.home_base) {
      // The route is one sortie: its fix may be as far off as the odometry can drift over it.
      double length = 0.0;
      for (size_t i = 1; i < setup_.route.size(); ++i)
        length += (setup_.route[i].position - setup_.route[i - 1].position).norm();
      CooperationConfig route = c;
      route.max_fix_jump_m = std::max(route.max_fix_jump_m, kRouteDriftPerMetre * length);
      route.max_fix_jump_rad = std::max(route.max_fix_jump_rad, kRouteTurnDriftPerMetre * length);
      coop_ = std::make_unique<HomeBaseCooperation>(setup_.name, setup_.home_base->visibleCorners(),
                                                    setup_.home_base->arm_length, shared_, route);
    }
  }
  if (!setup_.home_base) {  // the map frame is the start
    mapper_->relocate(Pose2());
    mapper_->keepPlacement();
    localized_ = true;
    localized_at_ = robot_.now();
  }
  odo_ = robot_.odometry();
  publish();
}

bool RobotAgent::done() const {
  if (mission_) return mission_->done();
  return done_;
}

std::string RobotAgent::phase() const {
  if (mission_) return toString(mission_->phase());
  if (!localized_) return done_ ? "done" : "look at home";
  if (!started_) return "at start";
  return done_ ? "done" : "route";
}

std::vector<Eigen::Vector2d> RobotAgent::teammatePositions() const {
  std::vector<Eigen::Vector2d> out;
  if (!team_) return out;
  // A teammate that stopped without knowing where it is, or not placed yet, reports no
  // position it stands at: it is seen (mapped, avoided) like the rest of the world.
  for (const TeammateReport& r : team_->others(setup_.name))
    if (r.localized && !r.lost) out.push_back(r.position);
  return out;
}

void RobotAgent::publish() {
  if (!team_) return;
  TeammateReport r;
  r.robot = setup_.name;
  r.localized = localized_;
  r.lost = mission_ ? mission_->lost() : (done_ && !localized_);
  r.position = estimate().translation();
  if (mission_) r.goal = mission_->explorationGoal();
  r.at_start = localized_ && !started_;
  team_->publish(r);
}

void RobotAgent::step() {
  if (setup_.mode == AgentSetup::Mode::kDriven)
    throw std::logic_error("RobotAgent::step: a driven robot steps with stepDriven");
  const double now = robot_.now();
  observe(now);
  act(decide(now, robot_.status()));
}

void RobotAgent::stepDriven(const MotionCommand& driven) {
  if (setup_.mode != AgentSetup::Mode::kDriven)
    throw std::logic_error("RobotAgent::stepDriven: the robot decides for itself");
  const double now = robot_.now();
  observe(now);
  latest_ = nullptr;
  const MotionSegment segment = segmentOf(driven);
  const bool drives = segment == MotionSegment::kStraight ||
                      (driven.kind == MotionCommand::Kind::kVelocity && driven.linear != 0.0);
  if (!localized_ && !done_ && driven_turned_ && drives) localizeStart(now);
  driven_turned_ = driven_turned_ || segment == MotionSegment::kTurn;
  if (localized_) started_ = true;
  act(driven);
}

void RobotAgent::observe(double now) {
  raw_now_ = robot_.odometry();
  odo_ = calibrate_ ? calibration_.calibrate(raw_now_) : raw_now_;
  sensed_ = false;
  if (now + 1e-9 >= next_sense_) {
    next_sense_ += sense_period_;
    sense();
  }
}

void RobotAgent::act(const MotionCommand& command) {
  command_ = command;
  robot_.command(command_);
  const MotionSegment segment = segmentOf(command_);
  turn_steps_ += segment == MotionSegment::kTurn;
  straight_steps_ += segment == MotionSegment::kStraight;
  publish();
}

void RobotAgent::sense() {
  std::optional<TrinocularFrame> frame = robot_.captureFrame();
  if (!frame) return;
  sensed_ = true;
  frame_segment_ = turn_steps_ + straight_steps_ == 0 ? MotionSegment::kStop
                   : turn_steps_ > straight_steps_    ? MotionSegment::kTurn
                                                      : MotionSegment::kStraight;
  turn_steps_ = straight_steps_ = 0;
  raw_.push_back(frame->odometry);
  // The frame's odometry as the agent uses it: its raw offset from now, on the calibrated
  // pose now (a frame is taken at most a sensing period before).
  if (calibrate_) frame->odometry = odo_ * (raw_now_.inverse() * frame->odometry);
  if (team_ && settings_.teammate_mask_m > 0.0 && localized_)
    mapper_->setTeammates(teammatePositions(), settings_.teammate_mask_m);
  latest_ = &mapper_->process(*frame, frame_segment_, lookingAtHomeBase());
  trackWhileDriving();
  ++frames_;
}

MotionCommand RobotAgent::decide(double now, const RobotStatus& status) {
  const Pose2 pose = mapper_->estimate(odo_);
  if (mission_) {
    if (team_) {
      std::vector<Eigen::Vector2d> goals;
      if (localized_)
        for (const TeammateReport& r : team_->others(setup_.name))
          if (r.goal) goals.push_back(*r.goal);
      mission_->setTeammates(localized_ ? teammatePositions() : std::vector<Eigen::Vector2d>{},
                             setup_.priority);
      if (settings_.coordinate) mission_->setTeammateGoals(goals);
    }
    const MotionCommand cmd =
        mission_->update(now, pose, mapper_->grid(), latest_, status.bumped, status.bump_bearing);
    latest_ = nullptr;
    if (mission_->phase() == MissionPhase::kAtStart) {
      if (!localized_) {
        localizeStart(now);
      } else if (teamReady(now)) {
        leaveStart(now);
      }
    } else if (coop_ && mission_->phase() == MissionPhase::kAtHome) {
      endSortie(now);
    }
    return cmd;
  }
  latest_ = nullptr;
  if (done_) return MotionCommand::stop();
  if (!localized_) {
    const MotionCommand cmd = look_->update(pose, now);
    if (!look_->done()) return cmd;
    localizeStart(now);
    return MotionCommand::stop();
  }
  if (!started_) {
    if (teamReady(now)) leaveStart(now);
    return MotionCommand::stop();
  }
  const MotionCommand cmd = route_->update(pose, now);
  if (!route_->done()) return cmd;
  if (!coop_) {
    done_ = true;
    return cmd;
  }
  if (!looked_home_) {
    // The route ends with a look at the home base where the robot started (unless its last
    // waypoint is one), for the sortie's home-base protocol.
    looked_home_ = true;
    if (!isLookAtHome(setup_.route.back())) {
      const MissionConfig c;
      route_ = std::make_unique<RouteFollower>(
          std::vector<Waypoint>{{home_.translation(), true, c.look_turn_rate, 0.0}}, RouteConfig{});
      return MotionCommand::stop();
    }
  }
  endSortie(now);
  return MotionCommand::stop();
}

bool RobotAgent::isLookAtHome(const Waypoint& w) const {
  return w.spin && (w.position - home_.translation()).norm() < 0.1;
}

bool RobotAgent::lookingAtHomeBase() const {
  if (!setup_.home_base) return false;
  if (mission_) {
    const MissionPhase p = mission_->phase();
    return p == MissionPhase::kLookAtHome || p == MissionPhase::kAtStart ||
           p == MissionPhase::kLookAgain || p == MissionPhase::kAtHome;
  }
  // A driver shows the robot the home base when it will: every frame may be a look.
  if (setup_.mode == AgentSetup::Mode::kDriven) return true;
  if (!started_) return true;  // the first look and the wait after it
  if (!route_) return false;
  if (looked_home_) return true;  // the route is over: the looks at home after it
  const size_t next = route_->nextWaypoint();
  return next < setup_.route.size() && isLookAtHome(setup_.route[next]);
}

// While the robot explores or heads home: the walls of the latest radial maps, at its current
// estimate, against the map frame's axes (wall_heading_gain); a correction turns the
// estimate's frame.
void RobotAgent::trackWhileDriving() {
  const bool driving =
      mission_ && !reapproaching_ &&
      (mission_->phase() == MissionPhase::kExplore || mission_->phase() == MissionPhase::kReturn);
  if (!driving || !headings_.enabled()) return;
  const std::vector<TraverseEntry>& entries = mapper_->traverse().entries;
  const size_t k =
      std::min(entries.size() - sortie_begin_, static_cast<size_t>(headings_.config().scans));
  std::vector<RadialMap> latest;
  for (size_t j = entries.size() - k; j < entries.size(); ++j) {
    latest.push_back(entries[j].scan);
    latest.back().odometry = mapper_->frame() * mapper_->rawOdometry()[j];
  }
  if (const std::optional<Pose2> c = headings_.update(latest))
    mapper_->setFrame(*c * mapper_->frame());
}

}  // namespace coopmap
