// Path planning on a realistic map: the true occupancy of worlds/lab_corridor.yaml at 5 cm,
// cropped to 400 x 400 cells (x -1..19 m, y -8..12 m: the lab, its two doors, the north
// corridor and the return corridor), cells off the floor unknown. Building the planning map
// (inflation for the B-14, distance transform, free regions) and RRTConnect + simplification
// from the lab to the return corridor and to the north corridor.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "core/planning/keep_clear.h"
#include "core/planning/path_planner.h"
#include "core/planning/planning_map.h"
#include "sim/world/ground_truth.h"
#include "sim/world/world.h"

namespace coopmap::bench {
namespace {

const Grid<CellState>& labCorridor400() {
  static const Grid<CellState> grid = [] {
    const sim::World world =
        sim::loadWorld(std::string(COOPMAP_SOURCE_DIR) + "/worlds/lab_corridor.yaml");
    MapLimits l;
    l.resolution = 0.05;
    l.origin = {-1.0, -8.0};
    l.width = l.height = 400;
    const GridU8 occupied = sim::trueOccupancy(world, l, RobotDescription{}.swept_height);
    const GridU8 floor = sim::floorMask(world, l);
    Grid<CellState> g(l, CellState::kUnknown);
    for (size_t i = 0; i < l.size(); ++i)
      if (floor.cells[i]) g.cells[i] = occupied.cells[i] ? CellState::kOccupied : CellState::kFree;
    return g;
  }();
  return grid;
}

void BM_PlanningMapBuild400(benchmark::State& state) {
  const Grid<CellState>& g = labCorridor400();
  const PlanningMapConfig config = PlanningMapConfig::forRobot(RobotDescription{});
  for (auto _ : state) {
    const PlanningMap m(g, config);
    benchmark::DoNotOptimize(m.clearance(200, 200));
  }
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// Arg 0: the query (0: lab start -> south end of the return corridor, through the back
// door; 1: lab start -> north corridor, through the lab door). Arg 1: simplify or not.
// Arg 2: keep clear of walls (PlannerConfig::preferred_margin 0.3 m) or not; shortfall_m2
// is the path's shortfall from that clearance (keepClear's measure), with or without.
// A new seed every iteration; counters report the median over the iterations.
void BM_PlanRRTConnect400(benchmark::State& state) {
  const PlanningMap map(labCorridor400(), PlanningMapConfig::forRobot(RobotDescription{}));
  const Pose2 start(1.5, 1.5, 0.0);  // jose's start
  const Eigen::Vector2d goal =
      state.range(0) == 0 ? Eigen::Vector2d(14.0, -6.0) : Eigen::Vector2d(18.0, 9.1);
  PlannerConfig config;
  config.simplify = state.range(1) != 0;
  config.preferred_margin = state.range(2) != 0 ? 0.3 : 0.0;
  KeepClearConfig clear;
  clear.clearance = map.config().robot_radius + 0.3;
  std::vector<double> ms, length, raw_length, waypoints, shortfall;
  int failed = 0;
  uint32_t seed = 1;
  for (auto _ : state) {
    config.seed = seed++;
    const auto t0 = std::chrono::steady_clock::now();
    const PlanResult r = PathPlanner(config).plan(map, start, goal);
    ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    if (!r.solved()) {
      ++failed;
      continue;
    }
    length.push_back(r.path.length());
    raw_length.push_back(r.raw_length);
    waypoints.push_back(static_cast<double>(r.path.waypoints.size()));
    shortfall.push_back(shortfallOf(r.path.waypoints, map, clear).integral);
  }
  state.counters["median_ms"] = median(ms);
  state.counters["length_m"] = median(length);
  state.counters["raw_length_m"] = median(raw_length);
  state.counters["waypoints"] = median(waypoints);
  state.counters["shortfall_m2"] = median(shortfall);
  state.counters["failed"] = failed;
}

BENCHMARK(BM_PlanningMapBuild400)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PlanRRTConnect400)
    ->ArgsProduct({{0, 1}, {0, 1}, {0, 1}})
    ->ArgNames({"query", "simplify", "keep_clear"})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace coopmap::bench
