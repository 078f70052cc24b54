#include "core/agent/robot_agent.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/correction/drift_correction.h"

namespace coopmap {

namespace {

// Looks again at the home base after one that found no fix (a person or a teammate in the
// view, a look from off the start), before the robot stops for good.
constexpr int kLooksAgain = 2;
// Pairs of radial maps a stereo distance scale needs before the calibration takes it, and
// the largest scale it takes: wheel odometry miscounting distance by more is no odometry.
constexpr int kMinStereoScalePairs = 10;
constexpr double kMaxStereoScale = 0.05;
// s a placed robot waits at its start for its teammates to be placed too (so that each
// leaves the others out of what it logged there) before it goes alone.
constexpr double kStartWait = 60.0;
// m from the home base's middle: a robot placed from farther drives to kLookDistance and
// looks again. The stereo's range error grows with the square of the range: from 2 m the far
// corner of the home base is 1-3 cm off and the fix about a degree, from 1.4 m a few tenths.
constexpr double kApproachFrom = 1.6;
constexpr double kLookDistance = 1.4;
// How far a route's home-base fix may move the robot, per metre of the route (m/m, rad/m): a
// generous bound on drifting odometry (the building's 78 m loop ends metres and tens of
// degrees off; the B-14's heading drifts 0.0055 rad/m).
constexpr double kRouteDriftPerMetre = 0.15;
constexpr double kRouteTurnDriftPerMetre = 0.01;

template <typename... Numbers>
std::string formatted(const char* format, Numbers... numbers) {
  char line[256];
  std::snprintf(line, sizeof line, format, numbers...);
  return line;
}

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

void RobotAgent::lookAgainAt(const Pose2& home, double now) {
  if (mission_) {
    mission_->returnAgain(home);
    return;
  }
  const MissionConfig c;
  route_ = std::make_unique<RouteFollower>(
      std::vector<Waypoint>{{home.translation(), true, c.look_turn_rate, 0.0}}, RouteConfig{});
  (void)now;
}

void RobotAgent::sortieEnded(bool fixed, int sortie, double now) {
  if (mission_) {
    if (fixed)
      mission_->continueAfterFix(now);
    else
      mission_->finish("stopped: no trusted home-base fix after sortie " + std::to_string(sortie) +
                           ", the robot does not know where it is",
                       false);
    return;
  }
  done_ = true;  // a route is one sortie
}

void RobotAgent::localizeStart(double now) {
  // The look just taken: the entries since it began, in the frame the mapper is in now.
  TraverseLog look;
  look.robot = mapper_->traverse().robot;
  look.entries.assign(
      mapper_->traverse().entries.begin() + static_cast<std::ptrdiff_t>(look_begin_),
      mapper_->traverse().entries.end());
  const StartFix fix =
      coopmap::localizeStart(look, *setup_.home_base, cooperation_config_.home_return);
  if (!fix.ok()) {
    ++start_looks_;
    if (start_looks_ <= kLooksAgain && setup_.mode != AgentSetup::Mode::kDriven) {
      log_.push_back(formatted("no home base from the look at the start at %.0f s: looking again "
                               "(%d of %d; ",
                               now, start_looks_, kLooksAgain) +
                     fix.method + ")");
      look_begin_ = mapper_->traverse().entries.size();
      if (mission_) {
        mission_->lookAgainAtStart(now);
      } else {
        const MissionConfig c;
        look_ = std::make_unique<RouteFollower>(
            std::vector<Waypoint>{
                {mapper_->estimate(odo_).translation(), true, c.look_turn_rate, 0.0}},
            RouteConfig{});
      }
      return;
    }
    const std::string why =
        std::string(setup_.mode == AgentSetup::Mode::kDriven ? "not placed: " : "stopped: ") +
        "the home base was not found from the start (" + fix.method +
        "), the robot does not know where it is";
    log_.push_back(why);
    if (mission_) mission_->finish(why, false);
    done_ = true;
    return;
  }
  // X_MO: the fix is in the frame the look was logged in (the odometry's, or the first fix's).
  const Pose2 X_MO = fix.correction * mapper_->frame();
  if (!start_fix_) {  // in the whole traverse's terms
    start_fix_ = fix;
    start_fix_->correction = X_MO;
    start_fix_->entry += look_begin_;
    start_fix_->turn_begin += look_begin_;
    for (size_t& i : start_fix_->view) i += look_begin_;
  }
  // Teammates placed already are left out of what was logged (the others, once placed, when
  // the robot leaves: leaveStart).
  if (team_ && settings_.teammate_mask_m > 0.0)
    mapper_->setTeammates(teammatePositions(), settings_.teammate_mask_m);
  mapper_->relocate(X_MO);
  const Pose2 at = mapper_->estimate(odo_);
  const Eigen::Vector2d mid =
      0.5 * (setup_.home_base->corners.first.position + setup_.home_base->corners.second.position);
  const double distance = (at.translation() - mid).norm();
  log_.push_back(formatted("%.0f s: placed by the home base %.2f m away at (%.3f m, %.3f m, "
                           "%.2f deg) in the map frame (",
                           now, distance, at.x, at.y, at.theta * 180.0 / M_PI) +
                 fix.method + ")");
  // (Only an exploring robot: a route is a script written from where the robot stands.)
  if (!approached_ && distance > kApproachFrom && setup_.mode == AgentSetup::Mode::kExplore) {
    approached_ = true;
    // Seen from afar, the home base's far corner is a few centimetres off in the stereo, and
    // the fix as many tenths of a degree: look again from nearer, facing it.
    const Eigen::Vector2d to =
        at.translation() + (distance - kLookDistance) * (mid - at.translation()).normalized();
    const double face = std::atan2(mid.y() - to.y(), mid.x() - to.x());
    look_begin_ = mapper_->traverse().entries.size();
    const MissionConfig c;
    const Waypoint again{to, true, c.look_turn_rate, c.look_wait_s, face};
    log_.push_back(
        formatted("%.0f s: driving %.2f m nearer to look again", now, distance - kLookDistance));
    if (mission_)
      mission_->lookFrom(again, now);
    else
      look_ = std::make_unique<RouteFollower>(std::vector<Waypoint>{again}, RouteConfig{});
    return;
  }
  localized_ = true;
  localized_at_ = now;
  // The start the robot comes back to: where it took the look it is placed by, with which
  // the first sortie begins (that look registers the home base).
  sortie_begin_ = placed_from_ = look_begin_ + fix.turn_begin;
  home_ = X_MO * mapper_->rawOdometry()[sortie_begin_];
  sortie_frame_ = X_MO;
}

bool RobotAgent::teamReady(double now) const {
  if (!team_) return true;
  if (now - localized_at_ >= kStartWait) return true;
  for (const TeammateReport& r : team_->others(setup_.name))
    if (!r.localized && !r.lost) return false;
  return true;
}

void RobotAgent::leaveStart(double now) {
  started_ = true;
  mapper_->keepPlacement();
  if (team_ && settings_.teammate_mask_m > 0.0) {
    mapper_->setTeammates(teammatePositions(), settings_.teammate_mask_m);
    mapper_->maskLogged(0);
  }
  if (mission_)
    mission_->startFrom(home_, now);
  else
    route_ = std::make_unique<RouteFollower>(setup_.route, RouteConfig{});
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

// The distance scale the cameras measured along the sortie's straight stretches (on the
// encoders' odometry), pooled with the earlier sorties', becomes the calibration's; the
// sortie itself, driven on the scale calibrated so far, is rescaled to it before it is
// corrected and posted (a home-base fix cannot see the scale, and closures to a map drawn at
// the odometry's own scale only confirm it).
void RobotAgent::calibrateStereoScale(TraverseLog& sortie) {
  if (raw_.size() < sortie_begin_ + sortie.entries.size()) return;
  if (stereo_measured_ != sortie_begin_) {  // once a sortie (a re-approach ends it again)
    stereo_measured_ = sortie_begin_;
    TraverseLog raw = sortie;
    for (size_t j = 0; j < raw.entries.size(); ++j)
      raw.entries[j].scan.odometry = raw_[sortie_begin_ + j];
    stereo_.add(stereoDistanceScale(raw));
  }
  if (stereo_.pairs() < kMinStereoScalePairs || std::abs(stereo_.scale()) > kMaxStereoScale) return;
  const double before = sortie_scale_;  // what the sortie was driven on
  const double after = stereo_.scale();
  calibration_.setDistanceScale(after);
  OdometryBias residual;
  residual.distance_scale = (1.0 + after) / (1.0 + before) - 1.0;
  Pose2 previous = sortie.entries.front().scan.odometry;
  for (size_t j = 1; j < sortie.entries.size(); ++j) {
    const Pose2 u = previous.inverse() * sortie.entries[j].scan.odometry;
    previous = sortie.entries[j].scan.odometry;
    sortie.entries[j].scan.odometry =
        sortie.entries[j - 1].scan.odometry * correctedIncrement(u, residual);
  }
}

// The robot is back at the home base and has looked at it: localize, correct and post the
// sortie (cooperation.h), apply the fix to its estimate, import the shared map, and send it
// out again (or stop it, without a trusted fix).
void RobotAgent::endSortie(double now) {
  const TraverseLog& all = mapper_->traverse();
  TraverseLog sortie;
  sortie.robot = all.robot;
  sortie.entries.assign(all.entries.begin() + static_cast<std::ptrdiff_t>(sortie_begin_),
                        all.entries.end());
  std::vector<Pose2> estimate;
  for (const TraverseEntry& e : sortie.entries) estimate.push_back(e.scan.odometry);
  // The sortie on its odometry chain from where it began (the tracker's steps are not motion).
  for (size_t j = 0; j < sortie.entries.size(); ++j)
    sortie.entries[j].scan.odometry = sortie_frame_ * mapper_->rawOdometry()[sortie_begin_ + j];
  if (calibrate_ && stereo_scale_) calibrateStereoScale(sortie);
  // The last look's localization, which endSortie takes over when the robot accepts it.
  std::optional<HomeBaseCooperation::Located> located;
  if (!reapproaching_) {
    // Back away from the start (odometry drifted): the home base looks different from
    // there. Drive to the start by a first fix and look again.
    located = coop_->locate(sortie, std::nullopt, look_from_);
    const SortieReport& first = located->rep;
    if (!first.fixed() && looks_again_ < kLooksAgain) {
      // No fix from this look (someone in the view, the look fitting the shared map
      // elsewhere): to the start as the live estimate places it (the estimate brought the
      // robot back there; on a long sortie the odometry chain drifts metres from it), and
      // look again.
      ++looks_again_;
      look_from_ = sortie.entries.size();
      log_.push_back(formatted("no fix from the look at %.0f s: looking again (%d of %d; ", now,
                               looks_again_, kLooksAgain) +
                     first.method + ")");
      lookAgainAt(home_, now);
      return;
    }
    const double off = (first.fix.translation() - home_.translation()).norm();
    if (first.fixed() && off > settings_.reapproach_m) {
      reapproaching_ = true;
      look_from_ = sortie.entries.size();
      std::string line =
          formatted("back %.2f m from the start at %.0f s: driving there by a first fix", off, now);
      if (first.fix_moved_m > 0.0)
        line += formatted(" (moved %.2f m by the shared map: the look fits it there)",
                          first.fix_moved_m);
      log_.push_back(line);
      // The start in the estimate's frame now (the fix is in the chain's frame).
      lookAgainAt(mapper_->frame() * sortie_frame_.inverse() * first.correction.inverse() * home_,
                  now);
      return;
    }
  }
  std::optional<Eigen::Vector2d> expected;
  if (reapproaching_) expected = home_.translation();
  if (reapproaching_ && looks_again_ < kLooksAgain) {
    located = coop_->locate(sortie, expected, look_from_);
    const SortieReport& second = located->rep;
    if (!second.fixed()) {
      // The look after driving to the start by the first fix disagrees with it (or found
      // nothing): one of the two was wrong and the robot cannot tell which. Back to the
      // start as the live estimate places it, and a fresh look there.
      reapproaching_ = false;
      look_from_ = sortie.entries.size();
      ++looks_again_;
      log_.push_back(formatted("no trusted fix from the look at %.0f s: looking again (%d of "
                               "%d; ",
                               now, looks_again_, kLooksAgain) +
                     second.method + ")");
      lookAgainAt(home_, now);
      return;
    }
  }
  reapproaching_ = false;
  looks_again_ = 0;
  const SortieReport rep =
      coop_->endSortie(sortie, expected, &estimate, look_from_, located ? &*located : nullptr);
  look_from_ = 0;
  if (rep.fixed()) mapper_->setFrame(rep.correction * sortie_frame_);
  // Joining the team's frame moved the start too.
  home_ = rep.team_frame * home_;
  if (mission_) mission_->moveHome(home_);
  if (rep.posted && calibrate_) calibration_.addSortie(rep.bias, rep.length_m);
  sortie_frame_ = mapper_->frame();
  sortie_scale_ = calibration_.bias().distance_scale;
  const SharedMapSnapshot snap = shared_->snapshot();
  if (snap.version > 0) mapper_->importMap(snap.log_odds, snap.seen);
  sortie_begin_ = all.entries.size();
  std::string line = formatted("sortie %d at %.0f s: ", rep.sortie, now) +
                     std::to_string(rep.entries) + " scans, " + (rep.fixed() ? "fixed" : "no fix") +
                     (rep.posted ? ", posted" : "");
  if (rep.fixed() && !rep.posted && !rep.post.reason.empty())
    line += ", not posted: " + rep.post.reason;
  line += " (" + rep.method;
  if (calibrate_ && calibration_.weight_m() > 0.0)
    line += formatted(
        "; odometry calibration: heading drift %.4f rad/m, turn scale %.4f, "
        "distance scale %.4f",
        calibration_.bias().heading_drift, calibration_.bias().turn_scale,
        calibration_.bias().distance_scale);
  log_.push_back(line + ")");
  sortieEnded(rep.fixed(), rep.sortie, now);
}

}  // namespace coopmap
