#include "core/planning/path_planner.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <ompl/base/MotionValidator.h>
#include <ompl/base/Planner.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/prm/PRMstar.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "core/planning/keep_clear.h"

namespace coopmap {

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {

// Seeds OMPL's seed generator once per process (see PathPlanner) and quiets its console.
void initOmplOnce() {
  static std::once_flag once;
  std::call_once(once, [] {
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    ompl::RNG::setSeed(20240607u);
  });
}

Eigen::Vector2d point(const ob::State* s) {
  const auto* v = s->as<ob::RealVectorStateSpace::StateType>();
  return {v->values[0], v->values[1]};
}

class MapValidityChecker : public ob::StateValidityChecker {
 public:
  MapValidityChecker(const ob::SpaceInformationPtr& si, const PlanningMap& map)
      : ob::StateValidityChecker(si), map_(map) {
    specs_.clearanceComputationType = ob::StateValidityCheckerSpecs::EXACT;
  }
  bool isValid(const ob::State* s) const override { return map_.freeAt(point(s)); }
  // m from the state's cell centre to the nearest blocked cell, less the radius and margin:
  // positive exactly on valid states.
  double clearance(const ob::State* s) const override {
    const Eigen::Vector2d p = point(s);
    const MapLimits& l = map_.limits();
    const int ix = l.cellX(p.x()), iy = l.cellY(p.y());
    if (!l.contains(ix, iy)) return 0.0;
    return map_.clearance(ix, iy) - map_.config().robot_radius - map_.config().margin;
  }

 private:
  const PlanningMap& map_;  // outlives the plan
};

// Exact: every cell a straight motion crosses must be free (no sampling resolution).
class MapMotionValidator : public ob::MotionValidator {
 public:
  MapMotionValidator(const ob::SpaceInformationPtr& si, const PlanningMap& map)
      : ob::MotionValidator(si), map_(map) {}
  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    return map_.segmentFree(point(s1), point(s2));
  }
  bool checkMotion(const ob::State* s1, const ob::State* s2,
                   std::pair<ob::State*, double>& last_valid) const override {
    std::optional<double> t = map_.firstBlockedOnSegment(point(s1), point(s2));
    if (!t) {
      // PlanningMap::segmentFree walks both ways: so does this.
      const std::optional<double> back = map_.firstBlockedOnSegment(point(s2), point(s1));
      if (!back) return true;
      t = 1.0 - *back;
    }
    // Back off from the blocked cell's boundary by a millionth of a cell.
    const double len = (point(s2) - point(s1)).norm() / map_.limits().resolution;
    const double back = len > 0.0 ? 1e-6 / len : 0.0;
    last_valid.second = std::max(0.0, *t - back);
    if (last_valid.first != nullptr)
      si_->getStateSpace()->interpolate(s1, s2, last_valid.second, last_valid.first);
    return false;
  }

 private:
  const PlanningMap& map_;
};

// A uniform sampler with its own seed, independent of OMPL's global seed sequence.
class SeededSampler : public ob::RealVectorStateSampler {
 public:
  SeededSampler(const ob::StateSpace* space, uint32_t seed) : ob::RealVectorStateSampler(space) {
    rng_.setLocalSeed(seed);
  }
};

// OMPL's PathSimplifier with its own seed.
class SeededSimplifier : public og::PathSimplifier {
 public:
  SeededSimplifier(const ob::SpaceInformationPtr& si, uint32_t seed) : og::PathSimplifier(si) {
    rng_.setLocalSeed(seed);
  }
};

ob::PlannerPtr makePlanner(const ob::SpaceInformationPtr& si, const PlannerConfig& c) {
  switch (c.planner) {
    case PlannerType::kRRTConnect: {
      auto p = std::make_shared<og::RRTConnect>(si);
      if (c.range > 0.0) p->setRange(c.range);
      return p;
    }
    case PlannerType::kPRMstar:
      return std::make_shared<og::PRMstar>(si);
    case PlannerType::kRRTstar: {
      auto p = std::make_shared<og::RRTstar>(si);
      if (c.range > 0.0) p->setRange(c.range);
      return p;
    }
  }
  throw std::logic_error("PathPlanner: unhandled planner type");
}

std::vector<Eigen::Vector2d> waypointsOf(const og::PathGeometric& path) {
  std::vector<Eigen::Vector2d> w;
  w.reserve(path.getStateCount());
  for (size_t i = 0; i < path.getStateCount(); ++i) {
    const Eigen::Vector2d p = point(path.getState(i));
    if (w.empty() || (p - w.back()).norm() > 1e-9) w.push_back(p);
  }
  return w;
}

double polylineLength(const std::vector<Eigen::Vector2d>& w) {
  double len = 0.0;
  for (size_t i = 1; i < w.size(); ++i) len += (w[i] - w[i - 1]).norm();
  return len;
}

// Deterministic string pulling: from each kept vertex jump to the farthest later vertex in
// straight sight. Never lengthens the path; removes the near-collinear vertices the random
// simplification leaves.
std::vector<Eigen::Vector2d> pullString(const std::vector<Eigen::Vector2d>& w,
                                        const PlanningMap& map) {
  if (w.size() <= 2) return w;
  std::vector<Eigen::Vector2d> out{w.front()};
  size_t i = 0;
  while (i + 1 < w.size()) {
    size_t j = w.size() - 1;
    while (j > i + 1 && !map.segmentFree(w[i], w[j])) --j;
    out.push_back(w[j]);
    i = j;
  }
  return out;
}

PlanResult failure(PlanStatus status, std::string reason) {
  PlanResult r;
  r.status = status;
  r.reason = std::move(reason);
  return r;
}

std::string where(const Eigen::Vector2d& p) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "(%.3f, %.3f)", p.x(), p.y());
  return buf;
}

// Why a point is not a valid robot position, for the status reason.
std::string invalidReason(const PlanningMap& map, const Eigen::Vector2d& p) {
  const MapLimits& l = map.limits();
  const int ix = l.cellX(p.x()), iy = l.cellY(p.y());
  if (!l.contains(ix, iy)) return where(p) + " m is outside the map";
  std::string cell = where(p) + " m (cell " + std::to_string(ix) + ", " + std::to_string(iy) + ")";
  if (map.blocked(ix, iy))
    return cell + " is in a blocked cell (occupied" +
           (map.config().allow_unknown ? "" : " or unknown") + ")";
  char buf[128];
  std::snprintf(buf, sizeof buf,
                " is %.3f m from the nearest blocked cell; the robot needs > %.3f m",
                map.clearance(ix, iy), map.config().robot_radius + map.config().margin);
  return cell + buf;
}

}  // namespace

const char* toString(PlannerType type) {
  switch (type) {
    case PlannerType::kRRTConnect:
      return "rrt-connect";
    case PlannerType::kPRMstar:
      return "prm-star";
    case PlannerType::kRRTstar:
      return "rrt-star";
  }
  return "?";
}

PlannerType parsePlannerType(const std::string& name) {
  for (PlannerType t : {PlannerType::kRRTConnect, PlannerType::kPRMstar, PlannerType::kRRTstar})
    if (name == toString(t)) return t;
  throw std::invalid_argument("planner: expected one of rrt-connect, prm-star, rrt-star, got '" +
                              name + "'");
}

const char* toString(PlanStatus status) {
  switch (status) {
    case PlanStatus::kSolved:
      return "solved";
    case PlanStatus::kStartInvalid:
      return "start invalid";
    case PlanStatus::kGoalInvalid:
      return "goal invalid";
    case PlanStatus::kNoPath:
      return "no path";
    case PlanStatus::kTimeout:
      return "timeout";
  }
  return "?";
}

void PlannerConfig::validate() const {
  auto bad = [](const std::string& f, const std::string& e, double v) {
    throw std::invalid_argument("planner config: field '" + f + "': expected " + e + ", got " +
                                std::to_string(v));
  };
  if (!(time_budget > 0.0 && time_budget <= 3600.0))
    bad("time_budget", "a time in (0, 3600] s", time_budget);
  if (!(range >= 0.0 && std::isfinite(range))) bad("range", "a distance >= 0 m", range);
  if (!(preferred_margin >= 0.0 && preferred_margin <= 5.0))
    bad("preferred_margin", "a margin in [0, 5] m", preferred_margin);
  if (simplify_rounds < 0 || simplify_rounds > 100)
    bad("simplify_rounds", "an integer in [0, 100]", simplify_rounds);
  if (static_cast<int>(planner) > static_cast<int>(PlannerType::kRRTstar))
    bad("planner", "a PlannerType", static_cast<int>(planner));
}

double PlannedPath::length() const { return polylineLength(waypoints); }

std::vector<MotionCommand> turnsAndStraights(const std::vector<Eigen::Vector2d>& waypoints,
                                             double start_heading,
                                             std::optional<double> goal_heading) {
  std::vector<MotionCommand> out;
  double heading = start_heading;
  auto turnTo = [&](double target) {
    const double turn = wrapAngle(target - heading);
    if (turn != 0.0) out.push_back(MotionCommand::turn(turn));
    heading = target;
  };
  for (size_t i = 1; i < waypoints.size(); ++i) {
    const Eigen::Vector2d d = waypoints[i] - waypoints[i - 1];
    const double len = d.norm();
    if (len <= 1e-9) continue;
    turnTo(std::atan2(d.y(), d.x()));
    out.push_back(MotionCommand::straight(len));
  }
  if (goal_heading) turnTo(*goal_heading);
  return out;
}

std::optional<size_t> firstBlockedSegment(const std::vector<Eigen::Vector2d>& waypoints,
                                          const PlanningMap& map) {
  if (waypoints.size() == 1 && !map.freeAt(waypoints.front())) return 0;
  for (size_t i = 0; i + 1 < waypoints.size(); ++i)
    if (!map.segmentFree(waypoints[i], waypoints[i + 1])) return i;
  return std::nullopt;
}

bool pathStillValid(const PlannedPath& path, const PlanningMap& map) {
  return !path.waypoints.empty() && !firstBlockedSegment(path.waypoints, map).has_value();
}

PathPlanner::PathPlanner(const PlannerConfig& config) : config_(config) {
  config_.validate();
  initOmplOnce();
}

PlanResult PathPlanner::plan(const PlanningMap& map, const Pose2& start,
                             const Eigen::Vector2d& goal,
                             std::optional<double> goal_heading) const {
  const Eigen::Vector2d s = start.translation();
  if (!map.freeAt(s)) return failure(PlanStatus::kStartInvalid, "start " + invalidReason(map, s));
  if (!map.freeAt(goal))
    return failure(PlanStatus::kGoalInvalid, "goal " + invalidReason(map, goal));
  if (!map.connected(s, goal))
    return failure(PlanStatus::kNoPath, "start " + where(s) + " m and goal " + where(goal) +
                                            " m lie in different free regions of the map");

  if (map.segmentFree(s, goal)) {  // in straight sight (or the same point): one segment
    PlanResult r;
    r.status = PlanStatus::kSolved;
    r.path.waypoints = keepClearOf(map, {s, goal});
    r.path.commands = turnsAndStraights(r.path.waypoints, start.theta, goal_heading);
    r.raw_waypoints = 2;
    r.raw_length = (goal - s).norm();
    r.reason = "the goal is in straight sight";
    if (r.path.waypoints.size() > 2)
      r.reason += "; " + std::to_string(r.path.waypoints.size() - 2) + " waypoints keep clear";
    return r;
  }

  const MapLimits& l = map.limits();
  auto space = std::make_shared<ob::RealVectorStateSpace>(2);
  ob::RealVectorBounds bounds(2);
  bounds.setLow(0, l.origin.x());
  bounds.setLow(1, l.origin.y());
  bounds.setHigh(0, l.origin.x() + l.width * l.resolution);
  bounds.setHigh(1, l.origin.y() + l.height * l.resolution);
  space->setBounds(bounds);
  auto samplers = std::make_shared<std::atomic<uint32_t>>(0);
  const uint32_t seed = config_.seed;
  space->setStateSamplerAllocator(
      [seed, samplers](const ob::StateSpace* sp) -> ob::StateSamplerPtr {
        return std::make_shared<SeededSampler>(sp, seed + 7919u * samplers->fetch_add(1));
      });
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker(std::make_shared<MapValidityChecker>(si, map));
  si->setMotionValidator(std::make_shared<MapMotionValidator>(si, map));
  si->setup();

  ob::ScopedState<ob::RealVectorStateSpace> from(space), to(space);
  from[0] = s.x();
  from[1] = s.y();
  to[0] = goal.x();
  to[1] = goal.y();
  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  pdef->setStartAndGoalStates(from, to);

  const ob::PlannerPtr planner = makePlanner(si, config_);
  planner->setProblemDefinition(pdef);
  planner->setup();
  ob::PlannerTerminationCondition ptc = ob::timedPlannerTerminationCondition(config_.time_budget);
  if (config_.max_iterations > 0) {
    auto count = std::make_shared<std::atomic<uint64_t>>(0);
    const uint64_t max = config_.max_iterations;
    ptc = ob::plannerOrTerminationCondition(
        ptc, ob::PlannerTerminationCondition([count, max] { return ++*count > max; }));
  }
  const ob::PlannerStatus status = planner->solve(ptc);
  if (status != ob::PlannerStatus::EXACT_SOLUTION || !pdef->hasExactSolution()) {
    char buf[96];
    std::snprintf(buf, sizeof buf, " found no path within %.3f s", config_.time_budget);
    return failure(PlanStatus::kTimeout,
                   std::string(toString(config_.planner)) + buf +
                       (config_.max_iterations > 0 ? " or its iterations" : "") +
                       " (OMPL: " + status.asString() + ")");
  }

  og::PathGeometric path(*pdef->getSolutionPath()->as<og::PathGeometric>());
  PlanResult r;
  r.status = PlanStatus::kSolved;
  const std::vector<Eigen::Vector2d> raw = waypointsOf(path);
  r.raw_waypoints = raw.size();
  r.raw_length = polylineLength(raw);
  std::vector<Eigen::Vector2d> w = raw;
  if (config_.simplify) {
    SeededSimplifier simplifier(si, seed ^ 0x9e3779b9u);
    for (int round = 0; round < config_.simplify_rounds; ++round) {
      simplifier.reduceVertices(path);
      simplifier.shortcutPath(path);
    }
    w = pullString(waypointsOf(path), map);
  }
  w = keepClearOf(map, std::move(w));
  // The motion validator checked every segment; a blocked one here is a bug, never a result.
  if (const auto bad = firstBlockedSegment(w, map)) {
    std::fprintf(stderr,
                 "PathPlanner: internal error: segment %zu of the planned path is blocked\n", *bad);
    std::abort();
  }
  r.path.waypoints = std::move(w);
  r.path.commands = turnsAndStraights(r.path.waypoints, start.theta, goal_heading);
  char buf[160];
  std::snprintf(buf, sizeof buf, "%s: %zu waypoints, %.2f m (raw %zu waypoints, %.2f m)",
                toString(config_.planner), r.path.waypoints.size(), r.path.length(),
                r.raw_waypoints, r.raw_length);
  r.reason = buf;
  return r;
}

std::vector<Eigen::Vector2d> PathPlanner::keepClearOf(const PlanningMap& map,
                                                      std::vector<Eigen::Vector2d> w) const {
  if (!(config_.preferred_margin > 0.0)) return w;
  KeepClearConfig c;
  c.clearance = map.config().robot_radius + config_.preferred_margin;
  return keepClear(std::move(w), map, c);
}

PathPlanner::Replan PathPlanner::replanIfBlocked(const PlanningMap& map, const PlannedPath& path,
                                                 const Pose2& current, size_t next_waypoint,
                                                 std::optional<double> goal_heading) const {
  if (next_waypoint >= path.waypoints.size())
    throw std::invalid_argument("replanIfBlocked: next_waypoint " + std::to_string(next_waypoint) +
                                " of a path of " + std::to_string(path.waypoints.size()) +
                                " waypoints");
  Replan out;
  PlannedPath rest;
  rest.waypoints.push_back(current.translation());
  for (size_t i = next_waypoint; i < path.waypoints.size(); ++i)
    if ((path.waypoints[i] - rest.waypoints.back()).norm() > 1e-9)
      rest.waypoints.push_back(path.waypoints[i]);
  if (rest.waypoints.size() == 1) rest.waypoints.push_back(rest.waypoints.front());
  if (pathStillValid(rest, map)) {
    rest.commands = turnsAndStraights(rest.waypoints, current.theta, goal_heading);
    out.result.status = PlanStatus::kSolved;
    out.result.reason = "the rest of the path is still free";
    out.result.raw_waypoints = rest.waypoints.size();
    out.result.raw_length = rest.length();
    out.result.path = std::move(rest);
    return out;
  }
  out.replanned = true;
  out.result = plan(map, current, path.waypoints.back(), goal_heading);
  return out;
}

}  // namespace coopmap
