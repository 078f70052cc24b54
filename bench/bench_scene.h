// A rendered lab frame shared by the benchmarks, with its ground-truth depth.
#pragma once

#include <memory>

#include "robots/robot_model.h"
#include "sim/simulator.h"

namespace coopmap::bench {

struct BenchScene {
  std::unique_ptr<sim::Simulator> sim;
  RobotModel model;
  TrinocularFrame frame;  // jose at its start pose in worlds/lab.yaml
  cv::Mat truth_depth;    // reference camera, metres along the optical axis
};

// Built once per process.
BenchScene& labScene();

// Bad-pixel rate (> 1 px) and density of a disparity image against the truth depth.
struct StereoScore {
  double bad_pixel_rate = 0.0;
  double density = 0.0;
};
StereoScore score(const cv::Mat& disparity, const cv::Mat& truth_depth, double focal_baseline,
                  int border);

}  // namespace coopmap::bench
