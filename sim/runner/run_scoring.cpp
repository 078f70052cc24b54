#include "sim/runner/run_scoring.h"

#include <algorithm>
#include <cmath>

#include "sim/runner/shared_maps.h"
#include "sim/world/ground_truth.h"

namespace coopmap {

RunScoring::RunScoring(const sim::World& world, const MapLimits& limits, std::vector<Pose2> X_WM,
                       const std::vector<RobotDescription>& descriptions, double timeline_period_s)
    : X_WM_(std::move(X_WM)), period_(timeline_period_s) {
  for (const Pose2& X : X_WM_)
    shared_frame_ =
        shared_frame_ && X.x == X_WM_[0].x && X.y == X_WM_[0].y && X.theta == X_WM_[0].theta;
  floor_ = sim::floorMask(world, limits, X_WM_.front());
  for (size_t k = 0; k < descriptions.size(); ++k) {
    truths_.push_back(sim::trueOccupancy(world, limits, descriptions[k].swept_height, X_WM_[k]));
    if (descriptions[k].swept_height > descriptions[tallest_].swept_height) tallest_ = k;
    starts_.push_back(X_WM_[k].inverse() * world.robots[k].start.translation());
    robots_.emplace_back();
    robots_.back().last_true = world.robots[k].start;
  }
}

void RunScoring::observeStep(size_t k, double t, const Pose2& true_pose, const Pose2& odometry,
                             const RobotAgent& agent) {
  Robot& r = robots_[k];
  r.groundtruth.push_back({t, X_WM_[k].inverse() * true_pose});
  r.odometry.push_back({t, odometry});
  r.estimate.push_back({t, agent.estimate()});
}

void RunScoring::observeMotion(size_t k, double dt, const Pose2& true_pose,
                               const std::vector<sim::ContactEvent>& log,
                               const std::string& phase) {
  constexpr double kDriving = 0.03, kTurning = 0.05;  // m/s, rad/s
  Robot& r = robots_[k];
  const double step = std::hypot(true_pose.x - r.last_true.x, true_pose.y - r.last_true.y);
  const double turn = std::abs(wrapAngle(true_pose.theta - r.last_true.theta));
  r.last_true = true_pose;
  PhaseTime& in = phaseNamed(r.phases, phase);
  in.time_s += dt;
  in.path_m += step;
  if (step > kDriving * dt)
    in.driving_s += dt;
  else if (turn > kTurning * dt)
    in.turning_s += dt;
  const Pose2 X_MW = X_WM_[k].inverse();
  for (size_t c = r.contacts.size(); c < log.size(); ++c)
    r.contacts.push_back(
        {log[c].time, sim::toString(log[c].kind), X_MW * log[c].point, X_MW * true_pose, phase});
}

void RunScoring::sample(double t, const std::vector<const RobotAgent*>& agents,
                        const LocalSharedMap* live, bool last) {
  if (last ? !timeline_.empty() && timeline_.back().t >= t : t + 1e-9 < next_sample_) return;
  if (!last) next_sample_ += period_;
  TimelineSample out;
  out.t = t;
  std::optional<OccupancyGrid> merged;
  if (live) merged = live->publishedGrid();
  for (size_t k = 0; k < agents.size(); ++k) {
    const Pose2 truth = robots_[k].groundtruth.back().pose;
    const Pose2 estimate = agents[k]->estimate();
    out.robot_error_m.push_back(std::hypot(truth.x - estimate.x, truth.y - estimate.y));
    out.robot_coverage.push_back(
        computeMapMetrics(agents[k]->mapper().grid(), truths_[k], starts_[0], &floor_).coverage);
    // Without sharing: what the robots have seen together (when they share a frame).
    if (!live && (k == 0 || shared_frame_)) {
      if (!merged)
        merged.emplace(agents[k]->mapper().grid());
      else
        mergeSeen(*merged, agents[k]->mapper().grid());
    }
  }
  out.shared_coverage = computeMapMetrics(*merged, sharedTruth(), starts_[0], &floor_).coverage;
  timeline_.push_back(std::move(out));
}

Pose2 RunScoring::truthAt(size_t k, double stamp) const {
  const std::vector<StampedPose2>& g = robots_[k].groundtruth;
  Pose2 out = g.front().pose;
  for (const StampedPose2& s : g) {
    if (s.stamp > stamp + 1e-9) break;
    out = s.pose;
  }
  return out;
}

RobotRunResult RunScoring::robotResult(size_t k, const RobotAgent& agent) const {
  const Robot& r = robots_[k];
  RobotRunResult out;
  out.name = agent.name();
  for (const PhaseTime& p : r.phases) out.path_length_m += p.path_m;  // every step is in one
  out.contacts = r.contacts;
  out.phases = r.phases;
  out.frames = agent.frames();
  out.route_complete = agent.done();
  out.groundtruth = r.groundtruth;
  out.odometry = r.odometry;
  out.estimate = r.estimate;
  out.traverse = agent.mapper().traverse();
  out.grid = agent.mapper().grid();
  out.truth = truths_[k];
  out.map_in_world = X_WM_[k];
  out.map = computeMapMetrics(agent.mapper().grid(), truths_[k], starts_[k], &floor_);
  out.phase = agent.phase();
  out.log = agent.log();
  out.calibration = agent.calibration();
  auto error = [&](int sortie, double stamp, const Pose2& fix) {
    const Pose2 t = truthAt(k, stamp);
    return FixError{sortie, stamp, std::hypot(fix.x - t.x, fix.y - t.y),
                    std::abs(wrapAngle(fix.theta - t.theta)) * 180.0 / M_PI};
  };
  if (const std::optional<StartFix>& fix = agent.startFix(); fix && fix->ok()) {
    out.odometry_in_map = fix->correction;
    out.start_fix_error =
        error(0, agent.mapper().traverse().entries[fix->entry].scan.stamp, fix->pose);
  }
  if (agent.startFix() && agent.localized()) {
    out.placed = true;
    for (const StampedPose2& e : r.estimate)
      if (e.stamp >= agent.localizedAt() - 1e-9) {
        out.placed_error = error(0, e.stamp, e.pose);
        break;
      }
  }
  if (const MissionAgent* m = agent.mission()) {
    out.exploration_complete = m->explorationComplete();
    out.goals_reached = m->goalsReached();
    out.goals_failed = m->goalsFailed();
    out.safety_stops = m->safetyStops();
    out.early_returns = m->earlyReturns();
    out.mission_event = m->lastEvent();
  }
  if (const HomeBaseCooperation* coop = agent.cooperation()) {
    for (const SortieReport& rep : coop->reports()) {
      ++out.sorties;
      out.sorties_fixed += rep.fixed();
      out.sorties_posted += rep.posted;
      if (rep.fixed()) out.fix_errors.push_back(error(rep.sortie, rep.fix_stamp, rep.fix));
    }
    out.corrected = coop->corrected();
  }
  return out;
}

}  // namespace coopmap
