// Corner landmarks: a whole-map corner search on a 40 m x 40 m grid at 5 cm (a building of
// rooms and corridors drawn into it), and one home-base localization (two corners).
#include <benchmark/benchmark.h>

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

BENCHMARK(BM_CornerSearch40mGrid)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HomeBaseLocalization)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace coopmap::bench
