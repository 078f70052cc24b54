// One whole sensing cycle of one robot, and its parts: render three views (OSMesa),
// trinocular stereo, radial map, occupancy grid update.
#include <benchmark/benchmark.h>

#include "bench/bench_scene.h"
#include "core/agent/mapper.h"
#include "sim/world/ground_truth.h"

namespace coopmap::bench {
namespace {

void BM_RenderThreeViews(benchmark::State& state) {
  BenchScene& s = labScene();
  for (auto _ : state) {
    TrinocularFrame f = s.sim->capture(0);
    benchmark::DoNotOptimize(f.reference.data);
  }
}

void BM_RadialMapAndGridUpdate(benchmark::State& state) {
  BenchScene& s = labScene();
  const RobotDescription& robot = s.model.description;
  TrinocularMatcher m(robot.rig, StereoConfig{});
  cv::Mat disparity;
  m.compute(s.frame.reference, s.frame.horizontal, s.frame.vertical, disparity);
  OccupancyGrid grid(sim::worldMapLimits(s.sim->world()), OccupancyConfig{});
  for (auto _ : state) {
    const RadialMap r = buildRadialMap(disparity, robot, RadialMapConfig{}, 0.0, s.frame.odometry);
    grid.insert(r, s.frame.odometry);
    benchmark::DoNotOptimize(grid.logOddsGrid().cells.data());
  }
}

void BM_SensingCycle(benchmark::State& state) {
  BenchScene& s = labScene();
  Mapper mapper(s.model.description, sim::worldMapLimits(s.sim->world()), MapperConfig{});
  for (auto _ : state) {
    const TrinocularFrame f = s.sim->capture(0);
    mapper.process(f);
    benchmark::DoNotOptimize(mapper.grid().logOddsGrid().cells.data());
  }
}

BENCHMARK(BM_RenderThreeViews)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RadialMapAndGridUpdate)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SensingCycle)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace coopmap::bench
