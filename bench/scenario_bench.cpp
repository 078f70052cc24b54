// Real-time factor of the whole simulation: two robots in the lab, all three cameras
// rendered at 10 Hz, physics at its step, the full core pipeline (stereo, radial maps,
// grid updates). Counters: simulated seconds per wall second and the wall-time split.
// For a one-core figure run with LP_NUM_THREADS=1 (llvmpipe otherwise uses every core).
#include <cmath>
#include <map>
#include <vector>

#include <benchmark/benchmark.h>

#include "sim/runner/drift_bench.h"
#include "sim/runner/world_run.h"

namespace coopmap::bench {
namespace {

void BM_RealTimeFactorTwoRobots10Hz(benchmark::State& state) {
  RunOptions o;
  o.world_file = std::string(COOPMAP_SOURCE_DIR) + "/worlds/lab.yaml";
  o.seed = 1;
  o.duration = 60.0;
  o.settings = [](AgentSettings& s) { s.sensing_rate = 10.0; };
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

namespace coopmap::bench {
namespace {

// Odometry drift over the paper's long traverse (worlds/lab_corridor.yaml, ~78 m), the
// route driven by the true pose, 20 seeds of an odometry preset of the B-14 file (0: the
// default, 1: utias_robot1, fitted to a real log). Paper (Fig. 6): 2.64 m and 25.4 degrees.
void BM_DriftLoop20Seeds(benchmark::State& state) {
  const char* presets[] = {"drifting", "utias_robot1"};
  std::vector<double> m, deg;
  double path = 0.0;
  for (auto _ : state) {
    m.clear();
    deg.clear();
    for (uint64_t seed = 1; seed <= 20; ++seed) {
      RunOptions o;
      o.world_file = std::string(COOPMAP_SOURCE_DIR) + "/worlds/lab_corridor.yaml";
      o.seed = seed;
      o.duration = 900.0;
      o.steer_by_truth = true;
      o.odometry = presets[state.range(0)];
      const RunResult r = runWorld(o);
      m.push_back(r.robots[0].odometry_error_m);
      deg.push_back(r.robots[0].odometry_error_deg);
      path = r.robots[0].path_length_m;
    }
  }
  auto mean = [](const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return s / v.size();
  };
  auto stddev = [&](const std::vector<double>& v) {
    const double mu = mean(v);
    double s = 0;
    for (double x : v) s += (x - mu) * (x - mu);
    return std::sqrt(s / (v.size() - 1));
  };
  state.counters["path_m"] = path;
  state.counters["error_m_mean"] = mean(m);
  state.counters["error_m_std"] = stddev(m);
  state.counters["error_deg_mean"] = mean(deg);
  state.counters["error_deg_std"] = stddev(deg);
}

BENCHMARK(BM_DriftLoop20Seeds)->Arg(0)->Arg(1)->Iterations(1)->Unit(benchmark::kSecond);

// The drift-error benchmark (`coopmap bench drift`): 20 seeds of the loop on the default
// odometry, home-base localization and every correction model; counters are the means over
// seeds of the ATE (m) per model and of the home-base fix error. The full table (and
// drift.csv) comes from `coopmap bench drift --out DIR`.
void BM_DriftCorrection20Seeds(benchmark::State& state) {
  DriftBenchResult r;
  for (auto _ : state) {
    DriftBenchOptions o;
    o.world_file = std::string(COOPMAP_SOURCE_DIR) + "/worlds/lab_corridor.yaml";
    o.seeds = 20;
    r = runDriftBench(o);
  }
  std::map<std::string, std::pair<double, int>> ate;
  double home_cm = 0.0;
  int fixes = 0;
  for (const DriftRow& row : r.rows) {
    if (row.status != "ok") continue;
    auto& [sum, n] = ate[row.model];
    sum += row.ate_rmse_m;
    ++n;
    if (row.model == "none") {
      home_cm += 100.0 * row.home_error_m;
      ++fixes;
    }
  }
  for (const auto& [model, sn] : ate) state.counters["ate_" + model] = sn.first / sn.second;
  state.counters["home_fix_cm"] = fixes > 0 ? home_cm / fixes : 0.0;
  state.counters["seeds_fixed"] = fixes;
}

BENCHMARK(BM_DriftCorrection20Seeds)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace coopmap::bench
