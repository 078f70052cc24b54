// Trinocular SAD (coopmap) against one-pair SAD and OpenCV's StereoBM and SGBM on the same
// rendered 160x120 lab frame, 32 disparities, one thread. Counters give the bad-pixel
// rate (> 1 px against the rendered depth) and the density of each.
#include <benchmark/benchmark.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/utility.hpp>

#include "bench/bench_scene.h"
#include "core/stereo/trinocular_matcher.h"

namespace coopmap::bench {
namespace {

void report(benchmark::State& state, const cv::Mat& disparity) {
  BenchScene& s = labScene();
  const StereoScore sc =
      score(disparity, s.truth_depth,
            s.model.description.rig.intrinsics.fx * s.model.description.rig.referenceBaseline(), 3);
  state.counters["bad_pixel_rate"] = sc.bad_pixel_rate;
  state.counters["density"] = sc.density;
}

void runCoopmap(benchmark::State& state, bool vertical) {
  cv::setNumThreads(1);
  BenchScene& s = labScene();
  StereoConfig c;
  c.use_vertical = vertical;
  TrinocularMatcher m(s.model.description.rig, c);
  cv::Mat disparity;
  for (auto _ : state) {
    m.compute(s.frame.reference, s.frame.horizontal, s.frame.vertical, disparity);
    benchmark::DoNotOptimize(disparity.data);
  }
  report(state, disparity);
}

void BM_CoopmapTrinocular(benchmark::State& state) { runCoopmap(state, true); }
void BM_CoopmapSinglePair(benchmark::State& state) { runCoopmap(state, false); }

void BM_OpenCvStereoBM(benchmark::State& state) {
  cv::setNumThreads(1);
  BenchScene& s = labScene();
  auto bm = cv::StereoBM::create(32, 7);
  cv::Mat raw, disparity;
  for (auto _ : state) {
    bm->compute(s.frame.reference, s.frame.horizontal, raw);
    benchmark::DoNotOptimize(raw.data);
  }
  raw.convertTo(disparity, CV_32F, 1.0 / 16.0);
  report(state, disparity);
}

void BM_OpenCvStereoSGBM3Way(benchmark::State& state) {
  cv::setNumThreads(1);
  BenchScene& s = labScene();
  auto sgbm = cv::StereoSGBM::create(0, 32, 5, 8 * 25, 32 * 25, 1, 0, 10, 0, 0,
                                     cv::StereoSGBM::MODE_SGBM_3WAY);
  cv::Mat raw, disparity;
  for (auto _ : state) {
    sgbm->compute(s.frame.reference, s.frame.horizontal, raw);
    benchmark::DoNotOptimize(raw.data);
  }
  raw.convertTo(disparity, CV_32F, 1.0 / 16.0);
  report(state, disparity);
}

BENCHMARK(BM_CoopmapTrinocular)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CoopmapSinglePair)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OpenCvStereoBM)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OpenCvStereoSGBM3Way)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace coopmap::bench
