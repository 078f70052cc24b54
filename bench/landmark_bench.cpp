// Corner landmarks: a whole-map corner search on a 40 m x 40 m grid at 5 cm (a building of
// rooms and corridors drawn into it), one home-base localization (two corners), and the
// search for a rival place for a look at home on such a shared map (the fix's rival check).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/agent/cooperation.h"
#include "core/landmarks/corner_detector.h"
#include "core/localization/home_base.h"

namespace coopmap::bench {
namespace {

// 800 x 800 cells: a grid of 4 m rooms with 1 m doorways; walls 2 cells thick, seen free
// inside, unknown inside the walls' far side.
GridU8 building() {
  MapLimits l;
  l.resolution = 0.05;
  l.width = l.height = 800;
  GridU8 g(l, static_cast<uint8_t>(CellClass::kFree));
  for (int iy = 0; iy < 800; ++iy)
    for (int ix = 0; ix < 800; ++ix) {
      const int rx = ix % 80, ry = iy % 80;
      const bool wall_x = rx < 2 && !(ry >= 30 && ry < 50);
      const bool wall_y = ry < 2 && !(rx >= 30 && rx < 50);
      if (wall_x || wall_y) g.at(ix, iy) = static_cast<uint8_t>(CellClass::kOccupied);
    }
  return g;
}

void BM_CornerSearch40mGrid(benchmark::State& state) {
  const GridU8 g = building();
  size_t found = 0;
  for (auto _ : state) {
    const CornerDetector det(g);
    found = det.findAll().corners.size();
    benchmark::DoNotOptimize(found);
  }
  state.counters["corners"] = static_cast<double>(found);
}

void BM_HomeBaseLocalization(benchmark::State& state) {
  // A 6 m x 6 m local map at 5 cm with the two home-base corners of one room.
  const GridU8 g = building();
  MapLimits l;
  l.resolution = 0.05;
  l.width = l.height = 120;
  GridU8 local(l, 0);
  for (int iy = 0; iy < 120; ++iy)
    for (int ix = 0; ix < 120; ++ix) local.at(ix, iy) = g.at(ix + 41, iy + 41);
  const CornerDetector det(local);
  const auto reg = registerHomeBase(det, {2.05, 2.05}, {2.05, 5.95}, 0.3);
  if (!reg.home) {
    state.SkipWithError(toString(reg.status));
    return;
  }
  for (auto _ : state) {
    const CornerDetector again(local);
    const HomeBaseFix fix = localizeAtHomeBase(again, *reg.home, Pose2(2.0, 2.0, 0.0), 0.5);
    benchmark::DoNotOptimize(fix.pose.x);
  }
}

void BM_RivalPlacement(benchmark::State& state) {
  // The building as a shared map, and a look from a room's corner: 300 points on the walls
  // within 3.5 m, as CooperationConfig's check uses (search 2 m, shifts of at least 0.5 m,
  // turns up to the benchmark's argument in degrees: 12, the default, and 4, session 12's).
  const GridU8 g = building();
  std::vector<int16_t> log_odds(g.limits.width * g.limits.height);
  std::vector<Eigen::Vector2d> walls;
  const Eigen::Vector2d pivot(1.0, 1.0);
  for (int iy = 0; iy < g.limits.height; ++iy)
    for (int ix = 0; ix < g.limits.width; ++ix) {
      const bool occ = g.at(ix, iy) == static_cast<uint8_t>(CellClass::kOccupied);
      log_odds[iy * g.limits.width + ix] = occ ? 500 : -500;
      const Eigen::Vector2d c = g.limits.cellCenter(ix, iy);
      if (occ && (c - pivot).norm() < 3.5) walls.push_back(c);
    }
  OccupancyGrid map(g.limits, OccupancyConfig{});
  map.assign(log_odds, std::vector<uint8_t>(log_odds.size(), 1));
  const ScanAligner aligner(map);
  std::vector<Eigen::Vector2d> look;
  for (size_t i = 0; i < walls.size(); i += std::max<size_t>(1, walls.size() / 300))
    look.push_back(walls[i]);
  const double turn = static_cast<double>(state.range(0)) * M_PI / 180.0;
  const RivalPlacement r = rivalPlacement(aligner, look, pivot, 2.0, 0.5, turn);
  for (auto _ : state) {
    const RivalPlacement again = rivalPlacement(aligner, look, pivot, 2.0, 0.5, turn);
    benchmark::DoNotOptimize(again);
  }
  state.counters["points"] = static_cast<double>(look.size());
  state.counters["here"] = r.here;
  state.counters["rival"] = r.score;
}

BENCHMARK(BM_CornerSearch40mGrid)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RivalPlacement)->Arg(12)->Arg(4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HomeBaseLocalization)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace coopmap::bench
