// RobotAgent at the home base (robot_agent.h): placing the robot at its start, and at the
// end of each sortie the fix, the distance scale, the correction and the post, and what
// follows a fix or the lack of one.
#include "core/agent/robot_agent.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

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

template <typename... Numbers>
std::string formatted(const char* format, Numbers... numbers) {
  char line[256];
  std::snprintf(line, sizeof line, format, numbers...);
  return line;
}

}  // namespace

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
        mission_->lookAgainAtStart();
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
      mission_->lookFrom(again);
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

// The distance scale the cameras measured along the sortie's straight stretches (on the
// encoders' odometry), pooled with the earlier sorties', becomes the calibration's; the
// sortie itself, driven on the scale calibrated so far, is rescaled to it before it is
// corrected and posted (a home-base fix cannot see the scale, and closures to a map drawn at
// the odometry's own scale only confirm it).
void RobotAgent::calibrateStereoScale(TraverseLog& sortie) {
  if (raw_.size() < sortie_begin_ + sortie.entries.size()) return;
  if (stereo_measured_ != sortie_begin_) {  // once a sortie (a re-approach ends it again)
    stereo_measured_ = sortie_begin_;
    // On the frames' centred windows' scans (Mapper::centredScans): shifted windows move the
    // edges of the jambs and corners the scale is matched on.
    const std::vector<RadialMap>& centred = mapper_->centredScans();
    TraverseLog raw = sortie;
    for (size_t j = 0; j < raw.entries.size(); ++j) {
      if (sortie_begin_ + j < centred.size()) raw.entries[j].scan = centred[sortie_begin_ + j];
      raw.entries[j].scan.odometry = raw_[sortie_begin_ + j];
    }
    stereo_.add(stereoDistanceScale(raw));
  }
  if (stereo_.pairs() < kMinStereoScalePairs) return;
  const double after = stereo_.scale();  // an M-estimate over every pair so far: once
  if (std::abs(after) > kMaxStereoScale) return;
  const double before = sortie_scale_;  // what the sortie was driven on
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
      reapproach_fix_ = first.correction;
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
  // Where the first fix places the robot now: at the start if it got there (a teammate
  // parked in the way may have kept it short of it, and it looked from there).
  std::optional<Eigen::Vector2d> expected;
  if (reapproaching_)
    expected =
        (reapproach_fix_ * sortie_frame_ * mapper_->frame().inverse() * mapper_->estimate(odo_))
            .translation();
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
