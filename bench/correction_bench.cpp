// Drift correction of the paper's long traverse (worlds/lab_corridor.yaml, one robot on the
// default drifting odometry, seed 1): home-base localization, each correction model, and
// rebuilding the map from the corrected traverse. The goal: correct + rebuild a
// whole traverse in 20 ms or less.
#include <benchmark/benchmark.h>

#include <memory>
#include <optional>

#include "core/correction/drift_correction.h"
#include "core/correction/home_return.h"
#include "sim/runner/world_run.h"
#include "sim/world/ground_truth.h"
#include "sim/world/world.h"

namespace coopmap::bench {
namespace {

struct Traverse {
  TraverseLog log;
  MapLimits limits;
  HomeBase home;
  double arm_length = 0.6;
  std::optional<OccupancyGrid> reference;
  PoseObservation observation;
};

Traverse& corridorTraverse() {
  static std::unique_ptr<Traverse> t = [] {
    auto t = std::make_unique<Traverse>();
    const std::string world_file = std::string(COOPMAP_SOURCE_DIR) + "/worlds/lab_corridor.yaml";
    const sim::World world = sim::loadWorld(world_file);
    RunOptions o;
    o.world_file = world_file;
    o.robots = 1;
    o.odometry = "drifting";
    o.steer_by_truth = true;
    o.duration = 3600;
    t->log = runWorld(o).robots[0].traverse;  // in the home base's frame
    const HomeBaseDesign design;
    t->limits = sim::worldMapLimits(world, 0.5, sim::mapFrameInWorld(world, design));
    t->arm_length = design.arm_length;
    t->home = design.visibleCorners();
    t->reference.emplace(homeBaseReferenceMap(t->log));
    t->observation =
        localizeFromLog(t->log, t->home, t->arm_length, {}, &*t->reference).observation;
    return t;
  }();
  return *t;
}

void BM_HomeReturnFromLog(benchmark::State& state) {
  Traverse& t = corridorTraverse();
  for (auto _ : state) {
    const HomeReturn r = localizeFromLog(t.log, t.home, t.arm_length, {}, &*t.reference);
    benchmark::DoNotOptimize(r.fix.pose.x);
  }
  state.counters["scans"] = static_cast<double>(t.log.entries.size());
}

void BM_Correct(benchmark::State& state) {
  Traverse& t = corridorTraverse();
  CorrectionConfig config;
  config.model = allCorrectionModels().at(static_cast<size_t>(state.range(0)));
  state.SetLabel(toString(config.model));
  for (auto _ : state) {
    const CorrectionResult r = correctTraverse(t.log, t.observation, config);
    benchmark::DoNotOptimize(r.poses.data());
  }
}

void BM_RebuildMap(benchmark::State& state) {
  Traverse& t = corridorTraverse();
  std::vector<Pose2> poses;
  for (const TraverseEntry& e : t.log.entries) poses.push_back(e.scan.odometry);
  for (auto _ : state) {
    const OccupancyGrid g = rebuildMap(t.log, poses, t.limits);
    benchmark::DoNotOptimize(g.logOddsGrid().cells.data());
  }
  state.counters["scans"] = static_cast<double>(t.log.entries.size());
}

void BM_CorrectAndRebuild(benchmark::State& state) {
  Traverse& t = corridorTraverse();
  CorrectionConfig config;
  config.model = CorrectionModel::kHeadingDrift;
  for (auto _ : state) {
    const CorrectionResult r = correctTraverse(t.log, t.observation, config);
    const OccupancyGrid g = rebuildMap(t.log, r.poses, t.limits);
    benchmark::DoNotOptimize(g.logOddsGrid().cells.data());
  }
}

BENCHMARK(BM_HomeReturnFromLog)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Correct)->DenseRange(0, 4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RebuildMap)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CorrectAndRebuild)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace coopmap::bench
