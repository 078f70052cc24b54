// Trinocular SAD (coopmap: centred windows, and shiftable ones) against one-pair SAD and
// OpenCV's StereoBM and SGBM (3-way) on the same rendered lab frames, one thread: 160x120
// with 32 disparities (window 7), 320x240/48 (window 9) and 640x480/64 (window 11). Counters
// give the bad-pixel rate (> 1 px against the rendered depth) and the density (valid /
// pixels with depth).
#include <benchmark/benchmark.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/utility.hpp>

#include "bench/bench_scene.h"
#include "core/stereo/stereo_eval.h"
#include "core/stereo/trinocular_matcher.h"

namespace coopmap::bench {
namespace {

struct Size {
  int width, height, disparities, window;
};
Size sizeOf(const benchmark::State& state) {
  const int w = static_cast<int>(state.range(0));
  return w == 160   ? Size{160, 120, 32, 7}
         : w == 320 ? Size{320, 240, 48, 9}
                    : Size{640, 480, 64, 11};
}

void report(benchmark::State& state, BenchScene& s, const cv::Mat& disparity, int border) {
  const double fb =
      s.model.description.rig.intrinsics.fx * s.model.description.rig.referenceBaseline();
  const DisparityScore sc =
      scoreDisparity(disparity, disparityFromDepth(s.truth_depth, fb), 1.0, border);
  state.counters["bad_pixel_rate"] = sc.bad_pixel_rate;
  state.counters["density"] = sc.density;
}

void runCoopmap(benchmark::State& state, bool vertical,
                int window_shift = StereoConfig{}.window_shift) {
  cv::setNumThreads(1);
  const Size z = sizeOf(state);
  BenchScene& s = labScene(z.width, z.height);
  StereoConfig c;
  c.num_disparities = z.disparities;
  c.window = z.window;
  c.use_vertical = vertical;
  c.window_shift = window_shift;
  TrinocularMatcher m(s.model.description.rig, c);
  cv::Mat disparity;
  for (auto _ : state) {
    m.compute(s.frame.reference, s.frame.horizontal, s.frame.vertical, disparity);
    benchmark::DoNotOptimize(disparity.data);
  }
  report(state, s, disparity, z.window / 2);
}

void BM_CoopmapTrinocular(benchmark::State& state) { runCoopmap(state, true); }
void BM_CoopmapSinglePair(benchmark::State& state) { runCoopmap(state, false); }
// Centred windows (window_shift 0): what the looks at the home base are matched on.
void BM_CoopmapTrinocularCentred(benchmark::State& state) { runCoopmap(state, true, 0); }

void BM_OpenCvStereoBM(benchmark::State& state) {
  cv::setNumThreads(1);
  const Size z = sizeOf(state);
  BenchScene& s = labScene(z.width, z.height);
  auto bm = cv::StereoBM::create(z.disparities, z.window);
  cv::Mat raw, disparity;
  for (auto _ : state) {
    bm->compute(s.frame.reference, s.frame.horizontal, raw);
    benchmark::DoNotOptimize(raw.data);
  }
  raw.convertTo(disparity, CV_32F, 1.0 / 16.0);
  report(state, s, disparity, z.window / 2);
}

void BM_OpenCvStereoSGBM3Way(benchmark::State& state) {
  cv::setNumThreads(1);
  const Size z = sizeOf(state);
  BenchScene& s = labScene(z.width, z.height);
  const int b = 5;
  auto sgbm = cv::StereoSGBM::create(0, z.disparities, b, 8 * b * b, 32 * b * b, 1, 0, 10, 0, 0,
                                     cv::StereoSGBM::MODE_SGBM_3WAY);
  cv::Mat raw, disparity;
  for (auto _ : state) {
    sgbm->compute(s.frame.reference, s.frame.horizontal, raw);
    benchmark::DoNotOptimize(raw.data);
  }
  raw.convertTo(disparity, CV_32F, 1.0 / 16.0);
  report(state, s, disparity, z.window / 2);
}

#define COOPMAP_STEREO_SIZES ->Arg(160)->Arg(320)->Arg(640)->Unit(benchmark::kMillisecond)
BENCHMARK(BM_CoopmapTrinocular) COOPMAP_STEREO_SIZES;
BENCHMARK(BM_CoopmapSinglePair) COOPMAP_STEREO_SIZES;
BENCHMARK(BM_CoopmapTrinocularCentred) COOPMAP_STEREO_SIZES;
BENCHMARK(BM_OpenCvStereoBM) COOPMAP_STEREO_SIZES;
BENCHMARK(BM_OpenCvStereoSGBM3Way) COOPMAP_STEREO_SIZES;

}  // namespace
}  // namespace coopmap::bench
