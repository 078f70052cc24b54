#include "sim/runner/shared_maps.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/mapping/map_metrics.h"

namespace coopmap {

namespace {

// How far a scripted traverse's home-base fix may move the robot, per metre driven (m/m,
// rad/m): a generous bound on drifting odometry (the building's 78 m loop ends metres and
// tens of degrees off; the B-14's heading drifts 0.0055 rad/m).
constexpr double kScriptedDriftPerMetre = 0.15;
constexpr double kScriptedTurnDriftPerMetre = 0.01;

}  // namespace

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

OccupancyGrid naiveSharedMap(const MapLimits& limits, const std::vector<const RobotAgent*>& agents,
                             const OccupancyConfig& published) {
  LocalSharedMap naive(limits, OccupancyConfig{}, "", published);
  for (const RobotAgent* agent : agents) {
    if (!agent->localized()) continue;
    const Pose2 placed =
        agent->startFix() && agent->startFix()->ok() ? agent->startFix()->correction : Pose2();
    TraverseLog log = agent->mapper().traverse();
    const std::vector<Pose2>& raw = agent->rawFrameOdometry();
    for (size_t i = 0; i < log.entries.size() && i < raw.size(); ++i)
      log.entries[i].scan.odometry = placed * raw[i];
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

SharedMapResult cooperativeSharedMaps(const LocalSharedMap& live,
                                      const std::vector<const RobotAgent*>& agents,
                                      const MapLimits& limits, const OccupancyConfig& published,
                                      const GridU8& truth, const GridU8& floor,
                                      const Pose2& start) {
  SharedMapResult shared;
  shared.protocol_grid = live.publishedGrid();
  shared.naive_grid = naiveSharedMap(limits, agents, published);
  for (const RobotAgent* agent : agents) {
    const HomeBaseCooperation* coop = agent->cooperation();
    if (!coop) continue;
    int posted = 0;
    for (const SortieReport& rep : coop->reports()) {
      posted += rep.posted;
      if (!rep.posted)
        shared.refused.push_back(agent->name() + " sortie " + std::to_string(rep.sortie) + ": " +
                                 rep.method);
    }
    shared.posts_accepted += posted;
    if (posted > 0) shared.posted.push_back(agent->name());
  }
  const Eigen::Vector2d from = start.translation();
  shared.protocol = computeMapMetrics(*shared.protocol_grid, truth, from, &floor);
  shared.imported = computeMapMetrics(live.grid(), truth, from, &floor);
  shared.naive = computeMapMetrics(*shared.naive_grid, truth, from, &floor);
  shared.computed = true;
  return shared;
}

SharedMapResult shareMaps(const HomeBaseDesign& design, const MapLimits& limits,
                          const GridU8& floor, const GridU8& truth,
                          const std::vector<const RobotAgent*>& agents, const std::string& closures,
                          const OccupancyConfig& published, const Pose2& start) {
  SharedMapResult out;
  LocalSharedMap protocol(limits, OccupancyConfig{}, "", published);
  for (const RobotAgent* agent : agents) {
    // From the look that placed the robot on: the protocol registers the home base there.
    TraverseLog log;
    log.robot = agent->mapper().traverse().robot;
    log.entries.assign(agent->mapper().traverse().entries.begin() +
                           static_cast<std::ptrdiff_t>(agent->placedFrom()),
                       agent->mapper().traverse().entries.end());
    if (!agent->localized()) {
      out.refused.push_back(log.robot + ": not placed at its start");
      continue;
    }
    CooperationConfig config;
    config.setClosureKinds(closures);
    // Its fix may be as far off as its odometry can have drifted over the whole traverse.
    double path = 0.0;  // by the robot's own odometry
    for (size_t i = 1; i < log.entries.size(); ++i)
      path += (log.entries[i].scan.odometry.translation() -
               log.entries[i - 1].scan.odometry.translation())
                  .norm();
    config.max_fix_jump_m = std::max(config.max_fix_jump_m, kScriptedDriftPerMetre * path);
    config.max_fix_jump_rad = std::max(config.max_fix_jump_rad, kScriptedTurnDriftPerMetre * path);
    HomeBaseCooperation coop(log.robot, design.visibleCorners(), design.arm_length, &protocol,
                             config);
    const SortieReport rep = coop.endSortie(log);
    if (rep.posted) {
      ++out.posts_accepted;
      out.posted.push_back(log.robot);
    } else {
      out.refused.push_back(
          log.robot + ": " +
          (rep.fixed() && !rep.post.reason.empty() ? rep.post.reason : rep.method));
    }
  }
  const Eigen::Vector2d from = start.translation();
  out.protocol_grid = protocol.publishedGrid();
  out.naive_grid = naiveSharedMap(limits, agents, published);
  out.protocol = computeMapMetrics(*out.protocol_grid, truth, from, &floor);
  out.imported = computeMapMetrics(protocol.grid(), truth, from, &floor);
  out.naive = computeMapMetrics(*out.naive_grid, truth, from, &floor);
  out.computed = true;
  return out;
}

}  // namespace coopmap
