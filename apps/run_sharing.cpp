#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "apps/robot_run.h"
#include "core/correction/drift_correction.h"
#include "core/correction/stereo_scale.h"
#include "core/mapping/map_metrics.h"

namespace coopmap::run_detail {

HomeBase nominalHomeBase(const sim::World& world) {
  HomeBase nominal;
  nominal.first.position = world.home_base.corners[0].position;
  nominal.first.heading = world.home_base.corners[0].heading;
  nominal.second.position = world.home_base.corners[1].position;
  nominal.second.heading = world.home_base.corners[1].heading;
  return nominal;
}

// Adds `b`'s evidence to `a` (log-odds summed and clamped, seen where either has seen):
// what two robots' maps show together.
void mergeSeen(OccupancyGrid& a, const OccupancyGrid& b) {
  std::vector<int16_t> lo = a.logOddsGrid().cells;
  std::vector<uint8_t> seen = a.seenGrid().cells;
  const std::vector<int16_t>& blo = b.logOddsGrid().cells;
  const std::vector<uint8_t>& bseen = b.seenGrid().cells;
  for (size_t i = 0; i < lo.size(); ++i) {
    lo[i] = static_cast<int16_t>(std::clamp(lo[i] + blo[i], -32000, 32000));
    seen[i] = seen[i] | bseen[i];
  }
  a.assign(lo, seen);
}

// The naive shared map: every radial map of every robot at its raw odometry pose.
OccupancyGrid naiveSharedMap(const MapLimits& limits, const std::vector<RobotRun>& runs,
                             const OccupancyConfig& published) {
  LocalSharedMap naive(limits, OccupancyConfig{}, "", published);
  for (const RobotRun& r : runs) {
    TraverseLog log = r.mapper->traverse();
    const std::vector<Pose2>& raw = r.raw;
    for (size_t i = 0; i < log.entries.size() && i < raw.size(); ++i)
      log.entries[i].scan.odometry = raw[i];
    // Radial maps whose odometry pose has drifted off the map are dropped (one would
    // otherwise refuse the whole post).
    MapPost post = naivePost(log, 1);
    std::erase_if(post.scans, [&](const PostedScan& p) {
      return !limits.contains(limits.cellX(p.pose.x), limits.cellY(p.pose.y));
    });
    naive.post(post);
  }
  return naive.publishedGrid();
}

// The paper's two ways of sharing: the home-base protocol (each traverse one sortie of
// HomeBaseCooperation: localized, corrected, checked, posted) and naive posting.
SharedMapResult shareMaps(const sim::World& world, const MapLimits& limits, const GridU8& floor,
                          const std::vector<RobotRun>& runs, const std::string& closures,
                          const OccupancyConfig& published) {
  SharedMapResult out;
  if (world.home_base.corners.size() != 2 || runs.empty()) return out;
  LocalSharedMap protocol(limits, OccupancyConfig{}, "", published);
  const HomeBase nominal = nominalHomeBase(world);
  // Each robot's traverse as one sortie of the autonomous runs' protocol
  // (core/agent/cooperation.h): localized at the home base, corrected (with the loop
  // closures `closures` names: none unless `coopmap run --closures` says, the paper's
  // heading-drift correction; within the traverse they cost a perfect-odometry lab tour
  // wall_recall 0.952 -> 0.894), checked against what is already shared (a return look that does
  // not look like the shared map's home is not shared), posted. Its fix may be as far off as its
  // odometry can have drifted over the whole traverse (kScriptedDriftPerMetre; at least what one
  // autonomous sortie's may be).
  for (const RobotRun& r : runs) {
    const TraverseLog& log = r.mapper->traverse();
    CooperationConfig config;
    config.setClosureKinds(closures);
    double path = 0.0;  // by the robot's own odometry
    for (size_t i = 1; i < log.entries.size(); ++i)
      path += (log.entries[i].scan.odometry.translation() -
               log.entries[i - 1].scan.odometry.translation())
                  .norm();
    config.max_fix_jump_m = std::max(config.max_fix_jump_m, kScriptedDriftPerMetre * path);
    config.max_fix_jump_rad = std::max(config.max_fix_jump_rad, kScriptedTurnDriftPerMetre * path);
    HomeBaseCooperation coop(log.robot, nominal, world.home_base.arm_length, &protocol, config);
    const SortieReport rep = coop.endSortie(log);
    if (rep.posted) {
      ++out.posts_accepted;
      out.posted.push_back(log.robot);
    } else {
      out.refused.push_back(log.robot + ": " +
                            (rep.fixed && !rep.post.reason.empty() ? rep.post.reason : rep.method));
    }
  }
  const GridU8& truth = tallestRobot(runs).truth;
  const Eigen::Vector2d start = runs.front().result.groundtruth.empty()
                                    ? world.robots.front().start.translation()
                                    : runs.front().result.groundtruth.front().pose.translation();
  out.protocol_grid = protocol.publishedGrid();
  out.naive_grid = naiveSharedMap(limits, runs, published);
  out.protocol = computeMapMetrics(*out.protocol_grid, truth, start, &floor);
  out.imported = computeMapMetrics(protocol.grid(), truth, start, &floor);
  out.naive = computeMapMetrics(*out.naive_grid, truth, start, &floor);
  out.computed = true;
  return out;
}

// While the robot explores or heads home: the latest radial maps at its current estimate,
// aligned to the shared map it imported (--tracking), and their walls to the building's axes
// (wall_heading_gain); each correction moves the estimate's frame.
void trackWhileDriving(RobotRun& r) {
  const bool driving =
      r.mission && !r.reapproaching &&
      (r.mission->phase() == MissionPhase::kExplore || r.mission->phase() == MissionPhase::kReturn);
  if (driving && (r.tracker.hasMap() || r.headings.enabled())) {
    // The latest radial maps at the current estimate: aligned to the shared map, and
    // their walls to the building's axes.
    const std::vector<TraverseEntry>& entries = r.mapper->traverse().entries;
    const size_t k = std::min(
        entries.size() - r.sortie_begin,
        static_cast<size_t>(std::max(r.tracker.config().scans, r.headings.config().scans)));
    std::vector<RadialMap> latest;
    for (size_t j = entries.size() - k; j < entries.size(); ++j) {
      latest.push_back(entries[j].scan);
      latest.back().odometry = r.mapper->frame() * r.mapper->rawOdometry()[j];
    }
    if (r.tracker.hasMap())
      if (const std::optional<Pose2> c = r.tracker.update(latest)) {
        r.mapper->setFrame(*c * r.mapper->frame());
        for (RadialMap& m : latest) m.odometry = *c * m.odometry;
      }
    if (const std::optional<Pose2> c = r.headings.update(latest))
      r.mapper->setFrame(*c * r.mapper->frame());
  }
}

// The distance scale the cameras measured along the sortie's straight stretches (on the
// encoders' odometry), pooled with the earlier sorties', becomes the calibration's; the
// sortie itself, driven on the scale calibrated so far, is rescaled to it before it is
// corrected and posted (a home-base fix cannot see the scale, and closures to a map drawn at
// the odometry's own scale only confirm it).
void calibrateStereoScale(RobotRun& r, TraverseLog& sortie) {
  if (r.raw.size() < r.sortie_begin + sortie.entries.size()) return;
  if (r.stereo_measured != r.sortie_begin) {  // once a sortie (a re-approach ends it again)
    r.stereo_measured = r.sortie_begin;
    TraverseLog raw = sortie;
    for (size_t j = 0; j < raw.entries.size(); ++j)
      raw.entries[j].scan.odometry = r.raw[r.sortie_begin + j];
    r.stereo.add(stereoDistanceScale(raw));
  }
  // Wheel odometry miscounting distance by more than kMaxStereoScale is no odometry; such a
  // figure is the matches' noise.
  if (r.stereo.pairs < kMinStereoScalePairs || std::abs(r.stereo.scale()) > kMaxStereoScale) return;
  const double before = r.sortie_scale;  // what the sortie was driven on
  const double after = r.stereo.scale();
  r.calibration.setDistanceScale(after);
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
// sortie (core/agent/cooperation.h), apply the fix to its estimate, import the shared map,
// and send it out again.
void endSortie(RobotRun& r, LocalSharedMap& live, double now, double reapproach_m, bool track) {
  const TraverseLog& all = r.mapper->traverse();
  TraverseLog sortie;
  sortie.robot = all.robot;
  sortie.entries.assign(all.entries.begin() + static_cast<std::ptrdiff_t>(r.sortie_begin),
                        all.entries.end());
  std::vector<Pose2> estimate;
  for (const TraverseEntry& e : sortie.entries) estimate.push_back(e.scan.odometry);
  // The sortie on its odometry chain from where it began (the tracker's steps are not motion).
  for (size_t j = 0; j < sortie.entries.size(); ++j)
    sortie.entries[j].scan.odometry = r.sortie_frame * r.mapper->rawOdometry()[r.sortie_begin + j];
  if (r.calibrate && r.stereo_scale) calibrateStereoScale(r, sortie);
  if (!r.reapproaching) {
    // Back away from the start (odometry drifted): the home base looks different from
    // there. Drive to the start by a first fix and look again.
    const SortieReport first = r.coop->locate(sortie, std::nullopt, r.look_from);
    if (!first.fixed && r.looks_again < kLooksAgain) {
      // No fix from this look (someone in the view, the look fitting the shared map
      // elsewhere): to the start as the live estimate places it (the mission's frame: the
      // estimate brought it back there), and look again. Not as the sortie's odometry chain
      // places it: on a long sortie the chain drifts metres from the estimate, and seed 48's
      // eric (--doorway-width 1.2) drove 2.4 m off into the lab's shelf to look there.
      ++r.looks_again;
      r.look_from = sortie.entries.size();
      char line[160];
      std::snprintf(line, sizeof line, "no fix from the look at %.0f s: looking again (%d of %d; ",
                    now, r.looks_again, kLooksAgain);
      r.result.sortie_log.push_back(line + first.method + ")");
      r.mission->returnAgain(r.home);
      return;
    }
    const double off = (first.fix.translation() - r.home.translation()).norm();
    if (first.fixed && off > reapproach_m) {
      r.reapproaching = true;
      r.look_from = sortie.entries.size();
      char line[160];
      std::snprintf(line, sizeof line,
                    "back %.2f m from the start at %.0f s: driving there by a first fix", off, now);
      std::string moved;
      if (first.fix_moved_m > 0.0) {
        char m[96];
        std::snprintf(m, sizeof m, " (moved %.2f m by the shared map: the look fits it there)",
                      first.fix_moved_m);
        moved = m;
      }
      r.result.sortie_log.push_back(line + moved);
      // The start in the estimate's frame now (the fix is in the chain's frame).
      r.mission->returnAgain(r.mapper->frame() * r.sortie_frame.inverse() *
                             first.correction.inverse() * r.home);
      return;
    }
  }
  std::optional<Eigen::Vector2d> expected;
  if (r.reapproaching) expected = r.home.translation();
  if (r.reapproaching && r.looks_again < kLooksAgain) {
    const SortieReport second = r.coop->locate(sortie, expected, r.look_from);
    if (!second.fixed) {
      // The look after driving to the start by the first fix disagrees with it (or found
      // nothing): one of the two was wrong (the first look's home base hidden, it fitted
      // something else) and the robot cannot tell which. Back to the start as the live
      // estimate places it, and a fresh look there.
      r.reapproaching = false;
      r.look_from = sortie.entries.size();
      ++r.looks_again;
      char line[160];
      std::snprintf(line, sizeof line,
                    "no trusted fix from the look at %.0f s: looking again (%d of %d; ", now,
                    r.looks_again, kLooksAgain);
      r.result.sortie_log.push_back(line + second.method + ")");
      r.mission->returnAgain(r.home);
      return;
    }
  }
  r.reapproaching = false;
  r.looks_again = 0;
  const SortieReport rep = r.coop->endSortie(sortie, expected, &estimate, r.look_from);
  r.look_from = 0;
  if (rep.fixed) r.mapper->setFrame(rep.correction * r.sortie_frame);
  if (rep.posted && r.calibrate) r.calibration.addSortie(rep.bias, rep.length_m);
  r.sortie_frame = r.mapper->frame();
  r.sortie_scale = r.calibration.bias().distance_scale;
  const SharedMapSnapshot snap = live.snapshot();
  if (snap.version > 0) {
    r.mapper->importMap(snap.log_odds, snap.seen);
    if (track) r.tracker.setMap(r.mapper->grid());
  }
  r.sortie_begin = all.entries.size();
  // The fix against the truth (the simulator knows it; the robot does not).
  std::string error;
  if (rep.fixed)
    for (auto it = r.result.groundtruth.rbegin(); it != r.result.groundtruth.rend(); ++it)
      if (it->stamp <= rep.fix_stamp + 1e-9) {
        const Pose2& t = it->pose;
        const double m = std::hypot(rep.fix.x - t.x, rep.fix.y - t.y);
        const double deg = std::abs(wrapAngle(rep.fix.theta - t.theta)) * 180.0 / M_PI;
        r.result.fix_errors.emplace_back(m, deg);
        char e[96];
        std::snprintf(e, sizeof e, " (%.1f cm, %.2f deg off the truth)", 100.0 * m, deg);
        error = e;
        break;
      }
  char line[256];
  std::snprintf(line, sizeof line, "sortie %d at %.0f s: %zu scans, %s%s%s", rep.sortie, now,
                rep.entries, rep.fixed ? "fixed" : "no fix", error.c_str(),
                rep.posted ? ", posted" : "");
  std::string calibration;
  r.result.calibration = r.calibration.bias();
  if (r.calibrate && r.calibration.weight_m() > 0.0) {
    char c[160];
    std::snprintf(c, sizeof c,
                  "; odometry calibration: heading drift %.4f rad/m, turn scale %.4f, distance "
                  "scale %.4f",
                  r.calibration.bias().heading_drift, r.calibration.bias().turn_scale,
                  r.calibration.bias().distance_scale);
    calibration = c;
  }
  const std::string refused = rep.fixed && !rep.posted && !rep.post.reason.empty()
                                  ? ", not posted: " + rep.post.reason
                                  : "";
  r.result.sortie_log.push_back(std::string(line) + refused + " (" + rep.method + calibration +
                                ")");
  if (rep.fixed)
    r.mission->continueAfterFix(now);
  else
    r.mission->finish("stopped: no trusted home-base fix after sortie " +
                          std::to_string(rep.sortie) + ", the robot does not know where it is",
                      false);
}

}  // namespace coopmap::run_detail
