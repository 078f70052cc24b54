// `coopmap stereo-eval`: trinocular stereo scored against ground truth, on real image
// triples (e.g. Tsukuba) or on frames rendered by the simulator.
#pragma once

#include <optional>
#include <string>

#include "core/stereo/stereo_eval.h"
#include "core/stereo/trinocular_matcher.h"

namespace coopmap {

struct StereoEvalOptions {
  // Image triple with ground truth...
  std::string reference, horizontal, vertical, truth;
  double truth_scale = 1.0;        // truth disparity = pixel value / truth_scale (Tsukuba: 16)
  double horizontal_offset = 1.0;  // partner offsets along x / y of the reference camera,
  double vertical_offset = -1.0;   // in units of one baseline (+x right, +y down)
  std::string rig;                 // ... or offsets (metres) from a robot model file
  // ... or frames rendered along the first robot's route of a world.
  std::string world;
  int frames = 10;  // how many frames, evenly spread over the route
  uint64_t seed = 1;
  StereoConfig stereo;
  int border = 0;       // pixels skipped on every side
  std::string png_dir;  // pictures of the (first) frame's disparities
};

struct StereoEvalResult {
  DisparityScore score;  // over all evaluated frames
  int frames = 0;
  double max_disparity = 0.0;
};

// Throws ConfigError / std::invalid_argument / std::runtime_error with a clear message.
StereoEvalResult runStereoEval(const StereoEvalOptions& options);

}  // namespace coopmap
