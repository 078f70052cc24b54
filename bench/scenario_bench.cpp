// Real-time factor of the whole simulation: two robots in the lab, all three cameras
// rendered at 10 Hz, physics at its step, the full core pipeline (stereo, radial maps,
// grid updates). Counters: simulated seconds per wall second and the wall-time split.
// For a one-core figure run with LP_NUM_THREADS=1 (llvmpipe otherwise uses every core).
#include <benchmark/benchmark.h>

#include "apps/run_world.h"

namespace coopmap::bench {
namespace {

void BM_RealTimeFactorTwoRobots10Hz(benchmark::State& state) {
  RunOptions o;
  o.world_file = std::string(COOPMAP_SOURCE_DIR) + "/worlds/lab.yaml";
  o.seed = 1;
  o.duration = 60.0;
  o.sensing_rate = 10.0;
  RunResult r;
  for (auto _ : state) r = runWorld(o);
  const double wall = r.wall_time_s;
  state.counters["real_time_factor"] = r.real_time_factor;
  state.counters["sim_s"] = r.sim_time_s;
  state.counters["physics_share"] = r.timing.physics_s / wall;
  state.counters["render_share"] = r.timing.render_s / wall;
  state.counters["stereo_share"] = r.timing.stereo_s / wall;
  state.counters["mapping_share"] = r.timing.mapping_s / wall;
}

BENCHMARK(BM_RealTimeFactorTwoRobots10Hz)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace coopmap::bench
